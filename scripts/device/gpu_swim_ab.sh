#!/usr/bin/env bash
# Run on a GPU machine from the repository root with a bundle made by bundle.sh: the
# swim of 10,000 fish (driver, placed deformation) for each binary in turn, ROUNDS
# rounds (default 3) of FRAMES frames (default 200), so that builds are compared side
# by side on the same GPU; OPTIONS, bench options for that entry (e.g.
# "bin/finflex|--normals jacobian"). One JSON line per run in OUT_FILE:
# {"binary" (its name and options), "round", "result"}; then a table of the runs
# (bench_table.py).
#
#   scripts/device/gpu_swim_ab.sh BUNDLE_DIR OUT_FILE BINARY[|OPTIONS] ...
set -uo pipefail
bundle=$1
out=$2
shift 2
export LD_LIBRARY_PATH="$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
source "$(dirname "$0")/register_nvidia_icd.sh"
: > "$out"
for round in $(seq "${ROUNDS:-3}"); do
  for entry in "$@"; do
    binary=${entry%%|*}
    options=""
    [[ $entry == *"|"* ]] && options=${entry#*|}
    # shellcheck disable=SC2086 # the options are words
    result=$("$binary" bench --mesh data/blub/fish.obj --rig data/rigs/blub_swim.rig.json \
      --swim --instances 10000 --frames "${FRAMES:-200}" --device NVIDIA --json $options) ||
      result=null
    echo "{\"binary\": \"$(basename "$binary")${options:+ $options}\", \"round\": $round, \"result\": $result}" >> "$out"
  done
done
python3 "$(dirname "$0")/bench_table.py" "$out"
