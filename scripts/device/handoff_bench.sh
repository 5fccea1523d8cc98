#!/usr/bin/env bash
# Run on a GPU machine from the repository root with a bundle made by bundle.sh: the
# output layouts of the hand-off (docs/handoff.md) against FinFlex's planes, each next
# to the write-only kernel through the same layout in the same run, on a device:
# the bend and the Blub rig, 4,000 instances on GPUs (1,000 on CPUs), every layout in
# slot and in mesh order, previous positions, half normals interleaved. One JSON line
# per run in OUT_DIR/handoff_<tag>.jsonl.
#
#   scripts/device/handoff_bench.sh BUNDLE_DIR OUT_DIR DEVICE TAG [INSTANCES]
set -uo pipefail
bundle=$1
out=$2
device=$3
tag=$4
instances=${5:-4000}
mkdir -p "$out"
export LD_LIBRARY_PATH="$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
log="$out/handoff_$tag.jsonl"
: > "$log"
bench() {
  "$bundle/bin/finflex" bench --mesh data/blub/fish.obj --instances "$instances" --frames 30 \
    --device "$device" --json "$@" >> "$log" || echo "{\"failed\": \"$*\"}" >> "$log"
}
for rig in "" "--rig data/rigs/blub.rig.json"; do
  for layout in planes interleaved compact snorm arrays; do
    for order in slots mesh; do
      # shellcheck disable=SC2086
      bench $rig --layout "$layout" --order "$order"
    done
  done
  # shellcheck disable=SC2086
  bench $rig --layout planes --previous
  # shellcheck disable=SC2086
  bench $rig --layout interleaved --normal-format half
done
python3 - "$log" <<'PY'
import json, sys
for line in open(sys.argv[1]):
    r = json.loads(line)
    if "failed" in r:
        print("failed:", r["failed"]); continue
    print(f'{r["deformation"]:<14} {r["layout"]:<12} {r["order"]:<6} prev={int(r["previous_positions"])} '
          f'{r["normal_format"]:<8} {r["seconds_per_frame_median"]*1e3:8.3f} ms  '
          f'{r["vertices_per_second"]/1e9:6.2f} Gvert/s  write fraction {r["write_fraction"]:.2f}')
PY
