#!/usr/bin/env bash
# The serial path against a baseline build, every figure a ratio measured in
# one run (the two builds alternate, so a shared host's drift reaches both):
#   1. seconds per Newton iteration (assembly + factorization + solve, from
#      summary.json) on cases/punch-plane-stress-fine at refine 4, 8 and 12
#      (23k, 93k, 209k dofs; symmetric: Cholesky) and on the return-mapping
#      friction case punch-friction-b refined to the same sizes (LU), first
#      increment of a 5-increment schedule;
#   2. peak memory per dof (same runs);
#   3. Newton iterations per increment on every shipped case and on the
#      50-increment plane-strain punch (refine 2 and 4), with the answers'
#      largest relative difference;
#   4. wall time of the default case and of the 50-increment runs.
# Usage: BASE=path/to/old/asperity benches/serial.sh [repeats]
#   e.g. git worktree add /tmp/base main~5 && (cd /tmp/base && cargo build --release)
#        BASE=/tmp/base/target/release/asperity benches/serial.sh 3
# NEW defaults to ./target/release/asperity (build it without --features
# parallel or pass --backend serial, which this script does).
set -euo pipefail
cd "$(dirname "$0")/.."
base=${BASE:?set BASE to the baseline asperity binary}
new=${NEW:-./target/release/asperity}
repeat=${1:-3}
out=${OUT:-target/bench-serial}
mkdir -p "$out"

# run TAG BIN ARGS...: one run, its summary in $out/TAG
run() {
    local tag=$1 bin=$2
    shift 2
    set +e
    "$bin" run "$@" --backend serial --quiet --out "$out/$tag" >/dev/null 2>"$out/$tag.err"
    local code=$?
    set -e
    # 3: stopped by --stop-after
    if [ $code -ne 0 ] && [ $code -ne 3 ]; then
        echo "run $tag failed ($code):" >&2
        cat "$out/$tag.err" >&2
        exit 1
    fi
}

echo "## 1-2. Newton iteration time and memory (first increment of 5), median of $repeat"
echo
echo "| case | refine | dofs | s/it base | s/it new | speed-up | B/dof base | B/dof new |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|"
for spec in "punch-plane-stress-fine 4" "punch-plane-stress-fine 8" "punch-plane-stress-fine 12" \
    "punch-friction-b 4" "punch-friction-b 8" "punch-friction-b 12"; do
    set -- $spec
    c=$1 r=$2
    for k in $(seq 1 "$repeat"); do
        for b in base new; do
            bin=$base
            [ $b = new ] && bin=$new
            run "it-$c-$r-$b-$k" "$bin" "cases/$c" --refine "$r" --increments 5 --stop-after 1
        done
    done
    python3 - "$out" "$c" "$r" "$repeat" <<'EOF'
import json, statistics, sys
out, c, r, n = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
def s(b, k):
    return json.load(open(f"{out}/it-{c}-{r}-{b}-{k}/summary.json"))
def per_it(d):
    return (d["assembly_seconds"] + d["solve_seconds"]) / d["factorizations"]
rows = {b: [s(b, k) for k in range(1, n + 1)] for b in ("base", "new")}
tb = statistics.median(per_it(d) for d in rows["base"])
tn = statistics.median(per_it(d) for d in rows["new"])
ratio = statistics.median(per_it(a) / per_it(b) for a, b in zip(rows["base"], rows["new"]))
dofs = rows["new"][0]["dofs"]
mb = lambda b: statistics.median(d["peak_memory_mb"] for d in rows[b]) * 1048576 / dofs
print(f"| {c} | {r} | {dofs:,} | {tb:.4f} | {tn:.4f} | {ratio:.2f} | {mb('base'):,.0f} | {mb('new'):,.0f} |")
EOF
done

echo
echo "## 3-4. Newton iterations per increment and wall time (median of $repeat)"
echo
echo "| run | increments | cutbacks base / new | it/inc base | it/inc new | wall base (s) | wall new (s) | speed-up | largest rel. difference |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|"
specs=()
for c in cases/*/; do
    c=$(basename "$c")
    [ "$c" = punch-plane-stress-fine ] && continue
    specs+=("$c|cases/$c")
done
specs+=("punch-plane-strain x50 refine 2|cases/punch-plane-strain --increments 50 --refine 2")
specs+=("punch-plane-strain x50 refine 4|cases/punch-plane-strain --increments 50 --refine 4")
for spec in "${specs[@]}"; do
    name=${spec%%|*}
    args=${spec#*|}
    tag=$(echo "$name" | tr ' ' '_')
    for k in $(seq 1 "$repeat"); do
        for b in base new; do
            bin=$base
            [ $b = new ] && bin=$new
            # shellcheck disable=SC2086
            run "run-$tag-$b-$k" "$bin" $args
        done
    done
    python3 - "$out" "$tag" "$name" "$repeat" <<'EOF'
import json, statistics, sys
out, tag, name, n = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
d = {b: [json.load(open(f"{out}/run-{tag}-{b}-{k}/summary.json")) for k in range(1, n + 1)]
     for b in ("base", "new")}
a, b = d["base"][0], d["new"][0]
def rel(x, y):
    return abs(x - y) / max(abs(x), abs(y), 1e-300)
diff = max(rel(a["final"][k], b["final"][k]) for k in a["final"]
           if isinstance(a["final"][k], float) and abs(a["final"][k]) > 0)
if a.get("first_yield") and b.get("first_yield"):
    diff = max(diff, rel(a["first_yield"]["load_factor"], b["first_yield"]["load_factor"]))
wb = statistics.median(x["wall_seconds"] for x in d["base"])
wn = statistics.median(x["wall_seconds"] for x in d["new"])
sp = statistics.median(x["wall_seconds"] / y["wall_seconds"] for x, y in zip(d["base"], d["new"]))
print(f"| {name} | {b['increments']} | {a['cutbacks']} / {b['cutbacks']} | "
      f"{a['newton_iterations'] / a['increments']:.2f} | {b['newton_iterations'] / b['increments']:.2f} | "
      f"{wb:.3f} | {wn:.3f} | {sp:.2f} | {diff:.1e} |")
EOF
done
