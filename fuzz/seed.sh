#!/usr/bin/env bash
# Seeds the fuzz corpus of `case_parser` with every shipped case and every case
# of the bad-input corpus: fuzz/corpus/case_parser/<folder>.toml. The corpus
# keeps most cases as a base plus a patch (tests/bad_inputs/README.md); the
# assembled cases come from its test, run here first.
set -euo pipefail
cd "$(dirname "$0")"
(cd .. && cargo test --release --quiet --test integration -- bad_inputs::every_corpus_folder_assembles >/dev/null)
assembled=../target/tmp/bad_inputs_assembled
dest=corpus/case_parser
mkdir -p "$dest"
n=0
for f in ../cases/*/case.toml "$assembled"/*/case.toml; do
    [ -f "$f" ] || continue
    cp "$f" "$dest/$(basename "$(dirname "$f")").toml"
    n=$((n + 1))
done
echo "seeded $n files into fuzz/$dest"
