#!/usr/bin/env bash
# Throughput of two builds of the finflex tool side by side, in one run, alternating
# (so that a busy machine slows both alike): the whole-body bend (paper, float32 and
# half normals) and the Blub rig (fused and passes), each as a fraction of the
# write-only kernel measured in the same `finflex bench` call. One JSON object per
# line on stdout, with "build" set to A or B and "round".
#
#   bench/compare_builds.sh OLD/finflex NEW/finflex INSTANCES [ROUNDS] [FRAMES] > out.jsonl
#   FINFLEX_DEVICE=NVIDIA bench/compare_builds.sh ... 4000 3 50
set -euo pipefail
a=$1
b=$2
instances=$3
rounds=${4:-3}
frames=${5:-30}
here=$(cd "$(dirname "$0")/.." && pwd)
mesh="$here/data/blub/fish.obj"
rig="$here/data/rigs/blub.rig.json"
device=()
[ -n "${FINFLEX_DEVICE:-}" ] && device=(--device "$FINFLEX_DEVICE")
cases=("--mode paper"
       "--mode paper --normal-format half"
       "--rig $rig --path fused"
       "--rig $rig --path passes")
for round in $(seq 1 "$rounds"); do
  for c in "${cases[@]}"; do
    for build in A B; do
      tool=$a
      [ "$build" = B ] && tool=$b
      # shellcheck disable=SC2086
      line=$("$tool" bench --mesh "$mesh" --instances "$instances" --frames "$frames" $c \
               "${device[@]}" --json)
      echo "{\"build\":\"$build\",\"round\":$round,${line#\{}"
    done
  done
done
