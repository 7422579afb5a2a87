#!/usr/bin/env bash
# Seeds the fuzz corpus of `case_parser` with every shipped case and every case
# of the bad-input corpus: fuzz/corpus/case_parser/<folder>.toml.
set -euo pipefail
cd "$(dirname "$0")"
dest=corpus/case_parser
mkdir -p "$dest"
n=0
for f in ../cases/*/case.toml ../tests/bad_inputs/*/case.toml; do
    [ -f "$f" ] || continue
    cp "$f" "$dest/$(basename "$(dirname "$f")").toml"
    n=$((n + 1))
done
echo "seeded $n files into fuzz/$dest"
