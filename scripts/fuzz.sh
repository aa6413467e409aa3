#!/usr/bin/env bash
# Runs every cargo-fuzz target (fuzz/) for SECONDS each (default 60), seeded with the five
# built-in models, the JSON rig and pose of the tests, and whatever earlier runs kept in
# fuzz/corpus/. Needs cargo-fuzz (`cargo install cargo-fuzz --locked`); the machine's one
# stable toolchain is allowed libFuzzer's (and AddressSanitizer's) flags by RUSTC_BOOTSTRAP=1. A crash stops the run
# with its input in fuzz/artifacts/TARGET/ (copy it into crates/chasles-skin/tests/
# fuzz-cases/ to keep it as a regression test). Prints each target's executions.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
export RUSTC_BOOTSTRAP=1
mkdir -p fuzz/corpus/gltf_bytes fuzz/corpus/gltf_fields fuzz/corpus/json_rig
cp crates/chasles-models/gltf/* fuzz/corpus/gltf_bytes/
cp crates/chasles-skin/tests/fuzz-cases/*.gl* fuzz/corpus/gltf_bytes/ 2>/dev/null || true
# The structure-aware target reads its edits from the bytes: any seed will do.
printf '\x01\x02\x03\x04\x05\x06\x07\x08' > fuzz/corpus/gltf_fields/seed
cat > fuzz/corpus/json_rig/rig.json <<'RIG'
{"positions": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]], "triangles": [[0,1,2],[1,3,2]],
 "joints": [{"name": "root", "parent": null}, {"name": "tip", "parent": 0, "translation": [0,1,0], "rotation": [1,0,0,0]}],
 "influences": [[[0,1]],[[0,0.5],[1,0.5]],[[1,1]],[[0,0.2],[1,0.8]]]}
RIG
printf '{"joints": {"0": {"rotation": [1, 0, 0, 0]}, "1": {"translation": [0, 1, 0]}}}' > fuzz/corpus/json_rig/pose.json
for target in gltf_bytes gltf_fields json_rig; do
    log="fuzz/artifacts/$target.log"
    mkdir -p "fuzz/artifacts/$target"
    (cd fuzz && cargo fuzz run "$target" "corpus/$target" -- \
        -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -max_len=4000000 \
        -print_final_stats=1) > "$log" 2>&1 || { tail -40 "$log"; echo "fuzz: $target crashed"; exit 1; }
    echo "fuzz: $target: $(grep -m1 'stat::number_of_executed_units' "$log" | awk '{print $2}') executions, $(grep -o 'cov: [0-9]*' "$log" | tail -1) , no crash"
done
