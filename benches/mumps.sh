#!/usr/bin/env bash
# MUMPS Cholesky (asperity's direct default for a symmetric tangent) against
# MUMPS LU on cases/punch-plane-stress-fine, 1 and 2 ranks, the two alternating
# so that a shared host's drift reaches both; first increment of 5.
# Needs the parallel build. Usage: benches/mumps.sh ["4 8 12"] [repeats]
# BIN=path runs another build; prints time per Newton iteration (assembly +
# solve over factorizations, summary.json), LU / Cholesky ratio (median of the
# adjacent pairs) and peak memory summed over the ranks.
set -euo pipefail
cd "$(dirname "$0")/.."
levels=${1:-"4 8 12"}
repeat=${2:-3}
bin=${BIN:-./target/release/asperity}
out=${OUT:-target/bench-mumps}
mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
echo "| refine | dofs | ranks | s/it Cholesky | s/it LU | LU / Cholesky | MB Cholesky | MB LU |"
echo "|---:|---:|---:|---:|---:|---:|---:|---:|"
for r in $levels; do
    for n in 1 2; do
        for k in $(seq 1 "$repeat"); do
            for f in cholesky lu; do
                set +e
                mpirun -n "$n" "$bin" run cases/punch-plane-stress-fine --refine "$r" --increments 5 \
                    --stop-after 1 --quiet --out "$out/$r-$n-$f-$k" -- -pc_type "$f" >/dev/null 2>&1
                code=$?
                set -e
                [ $code -eq 0 ] || [ $code -eq 3 ] || { echo "run $r $n $f failed ($code)" >&2; exit 1; }
            done
        done
        python3 - "$out" "$r" "$n" "$repeat" <<'PY'
import json, statistics, sys
out, r, n, k = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
d = {f: [json.load(open(f"{out}/{r}-{n}-{f}-{i}/summary.json")) for i in range(1, k + 1)]
     for f in ("cholesky", "lu")}
for f in d:
    assert all(f in x["linear_solver"] for x in d[f]), d[f][0]["linear_solver"]
t = lambda x: (x["assembly_seconds"] + x["solve_seconds"]) / x["factorizations"]
tc = statistics.median(t(x) for x in d["cholesky"])
tl = statistics.median(t(x) for x in d["lu"])
ratio = statistics.median(t(b) / t(a) for a, b in zip(d["cholesky"], d["lu"]))
mc = statistics.median(x["peak_memory_mb"] for x in d["cholesky"])
ml = statistics.median(x["peak_memory_mb"] for x in d["lu"])
print(f"| {r} | {d['lu'][0]['dofs']:,} | {n} | {tc:.3f} | {tl:.3f} | {ratio:.2f} | {mc:.0f} | {ml:.0f} |")
PY
    done
done
