#!/usr/bin/env bash
# Throughput sweep with `finflex bench`: instances x meshes x deformations x output
# formats (float32 normals; half normals for the paper bend and the fused rig), one JSON
# object per line on stdout. Combinations the device cannot hold (an output array
# above its largest allocation) are reported on stderr and skipped.
#
#   bench/sweep.sh [FINFLEX] [FRAMES] > results.jsonl
#   FINFLEX_DEVICE=H100 bench/sweep.sh build/apps/finflex 20 > h100.jsonl
#
# Meshes: the bundled fish (945, 2,188 and 10,786 vertices) and a 112,642-vertex fish
# Loop-subdivided from the bundled control cage (made here, in a temporary folder).
set -uo pipefail
finflex=${1:-build/apps/finflex}
frames=${2:-10}
here=$(cd "$(dirname "$0")/.." && pwd)
data="$here/data"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
"$finflex" subdivide --in "$data/blub/fish_control_mesh.obj" --levels 5 --out "$scratch/fish_112k.obj" >&2

meshes=("$data/blub/fish_low_resolution.obj" "$data/barramundi/BarramundiFish.gltf"
        "$data/blub/fish.obj" "$scratch/fish_112k.obj")
rigs=("$data/rigs/blub_low_resolution.rig.json" "$data/rigs/barramundi.rig.json" "$data/rigs/blub.rig.json" "")
device=()
[ -n "${FINFLEX_DEVICE:-}" ] && device=(--device "$FINFLEX_DEVICE")

run() {
  "$finflex" bench "$@" --frames "$frames" "${device[@]}" --json || echo "skipped: $*" >&2
}

for k in "${!meshes[@]}"; do
  mesh=${meshes[$k]}
  for instances in 1 10 100 1000 4000; do
    for mode in paper exact; do
      run --mesh "$mesh" --instances "$instances" --mode "$mode"
    done
    run --mesh "$mesh" --instances "$instances" --mode paper --normal-format half
    if [ -n "${rigs[$k]}" ]; then
      for path in fused passes; do
        run --mesh "$mesh" --instances "$instances" --rig "${rigs[$k]}" --path "$path"
      done
      run --mesh "$mesh" --instances "$instances" --rig "${rigs[$k]}" --path fused \
        --normal-format half
    fi
  done
done
