#!/usr/bin/env bash
# Run on a GPU machine from the repository root with a bundle made by bundle.sh: the
# swim's speed table of docs/swimming.md, one JSON line per run in OUT_DIR/swim.jsonl
# (each with its write-only kernel through the same layout, in the same process):
# 10,000 swimming fish of the bundled Blub (driver, rig_prepare, placed deformation),
# float32 normals three times (the machine is shared) and once with the tank stepping
# inside the frame loop (--swim-inputs live), half normals, Jacobian normals,
# 2 and 4 instances per work-item; then the swim rig without the driver or placement
# and the whole-body bend, at the same count, for reference.
#
#   scripts/device/swim_bench.sh BUNDLE_DIR OUT_DIR [DEVICE] [FISH]
set -uo pipefail
bundle=$1
out=$2
device=${3:-NVIDIA}
fish=${4:-10000}
mkdir -p "$out"
export LD_LIBRARY_PATH="$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
source "$(dirname "$0")/register_nvidia_icd.sh"
log="$out/swim.jsonl"
: > "$log"
bench() {
  local case=$1
  shift
  local result
  result=$("$bundle/bin/finflex" bench --mesh data/blub/fish.obj --instances "$fish" \
    --frames 50 --device "$device" --json "$@") || result=null
  echo "{\"case\": \"$case\", \"result\": $result}" >> "$log"
}
swim=(--rig data/rigs/blub_swim.rig.json)
for run in 1 2 3; do bench "swim, float32 normals, run $run" "${swim[@]}" --swim; done
bench "swim, float32 normals, the tank stepping in the frame loop" "${swim[@]}" --swim \
  --swim-inputs live
bench "swim, half normals" "${swim[@]}" --swim --normal-format half
bench "swim, Jacobian normals" "${swim[@]}" --swim --normals jacobian
bench "swim, 2 instances per work-item" "${swim[@]}" --swim --per-item 2
bench "swim, 4 instances per work-item" "${swim[@]}" --swim --per-item 4
bench "swim rig, no driver, not placed" "${swim[@]}"
bench "whole-body bend" --mode paper
python3 "$(dirname "$0")/bench_table.py" "$log"
