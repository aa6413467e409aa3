#!/usr/bin/env bash
# Runs every cargo-fuzz target (fuzz/) for SECONDS each (default 60), seeded with the five
# built-in models, the JSON rig and pose of the tests, key files, blend cases and JSON lines
# of every form, and whatever earlier runs kept in fuzz/corpus/. TARGETS (optional, after
# SECONDS) picks some. Needs cargo-fuzz (`cargo install cargo-fuzz --locked`); the machine's one
# stable toolchain is allowed libFuzzer's (and AddressSanitizer's) flags by RUSTC_BOOTSTRAP=1. A crash stops the run
# with its input in fuzz/artifacts/TARGET/ (copy it into crates/chasles-skin/tests/
# fuzz-cases/ to keep it as a regression test). Prints each target's executions.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
export RUSTC_BOOTSTRAP=1
mkdir -p fuzz/corpus/{gltf_bytes,gltf_fields,json_rig,key_file,blend_cases,convert_jsonl}
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
# Key files: the first byte picks the format ('0' TOML, '1' JSON).
cat > fuzz/corpus/key_file/keys.toml <<'KEYS'
0order = "ZYX"
[[keys]]
angle = 1.0
axis = [1, 3, 0]
time = 0
[[keys]]
quat = [1, 0, 0, 0]
time = 1
[[keys]]
euler = [0.3, 0, 0]
order = "xyz"
time = 3
[spring]
levels = [9, 17]
iterations = [5, 5]
step = "accelerated:0.05"
width = "angle"
key_weight = 1.3
start = "squad"
KEYS
printf '1{"order": "xyz", "keys": [{"euler": [0.1, 0.2, 0.3]}, {"quat": [0, 1, 0, 0]}, {"angle": 2, "axis": [0, 0, 1]}]}' > fuzz/corpus/key_file/keys.json
printf '1[{"quat": [1, 0, 0, 0], "time": 0}, {"quat": [0.6, 0.8, 0, 0], "time": 2}]' > fuzz/corpus/key_file/array.json
# Blend cases: the first byte picks the method (its index in Method::ALL).
for m in 0 1 2 3 4 5 6 7; do
    printf "\\x0$m" > "fuzz/corpus/blend_cases/case$m.json"
    cat >> "fuzz/corpus/blend_cases/case$m.json" <<'CASE'
[{"transforms": [{"rotation": [1,0,0,0], "translation": [1,2,3]}, {"matrix": [[0,-1,0,1],[1,0,0,0],[0,0,1,0],[0,0,0,1]]},
  {"dq": [0.6,0.8,0,0,0,0,0.5,0]}, {"screw": {"axis": [0,0,1], "point": [1,0,0], "angle": 1, "translation": 2}}],
  "weights": [0.1, 0.2, 0.3, 0.4], "center": [0, 1, 0], "precision": 1e-9, "max_iterations": 20},
 {"from": {"quat": [1,0,0,0]}, "to": {"euler": [0.1,0.2,0.3], "order": "ZYX"}, "t": 0.25},
 {"transforms": [{"axis": [1,0,0], "angle": 3}, {"rotvec": [0,0,3.1]}], "weights": [0.5, 0.5]}]
CASE
done
# JSON lines: the first two bytes pick --from, --to and --precision.
printf '\x01\x05' > fuzz/corpus/convert_jsonl/lines.jsonl
cat >> fuzz/corpus/convert_jsonl/lines.jsonl <<'LINES'
[1, 0, 0, 0]
{"quat": [0.6, 0.8, 0, 0]}
{"rotation": [1, 0, 0, 0], "translation": [1, 2, 3]}
{"matrix": [[0, -1, 0], [1, 0, 0], [0, 0, 1]]}
{"dq": [1, 0, 0, 0, 0, 0.5, 0, 0]}
{"euler": [0.1, 0.2, 0.3], "order": "XYZ", "gimbal_lock": false}
{"axis": [0, 0, 1], "angle": 1.5}
{"rotvec": [0, 3, 0]}
{"screw": {"axis": [0, 0, 1], "point": [1, 0, 0], "angle": 1, "translation": 2, "moment": [0, -1, 0], "pitch": 2}}

{"quat": [0, 0, 0, 0]}
LINES
targets="${2:-gltf_bytes gltf_fields json_rig key_file blend_cases convert_jsonl}"
for target in $targets; do
    log="fuzz/artifacts/$target.log"
    mkdir -p "fuzz/artifacts/$target"
    # Text inputs stay small (a key file or a case is hundreds of bytes); glTF needs room
    # for the models. stderr is closed (-close_fd_mask=2): the CLI's modules print notes.
    case "$target" in gltf_*) max_len=4000000 ;; *) max_len=65536 ;; esac
    (cd fuzz && cargo fuzz run "$target" "corpus/$target" -- \
        -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -max_len="$max_len" \
        -close_fd_mask=2 -print_final_stats=1) > "$log" 2>&1 || { tail -40 "$log"; echo "fuzz: $target crashed"; exit 1; }
    echo "fuzz: $target: $(grep -m1 'stat::number_of_executed_units' "$log" | awk '{print $2}') executions, $(grep -o 'cov: [0-9]*' "$log" | tail -1) , no crash"
done
