#!/usr/bin/env bash
# Run on a GPU machine from the repository root with a bundle made by bundle.sh and the
# GL loader packages (GLVND's libEGL, libGL, libOpenGL; libepoxy) unpacked into /:
# the tank of `finflex swim` with rendering, 1,000 fish of the bundled species, on the
# NVIDIA GPU for both OpenCL and OpenGL (EGL device, no display): frames per second and
# each frame's shares (deform, hand-off, draw, read-back, files, annotation) and the
# hand-off's path (shared: OpenCL writes the GL buffers; copy: through the host, with
# why), drawn only, with every frame written as a PNG, and as a dataset (--annotate),
# then the path and hand-off time of each run's summary. Writes
# OUT_DIR/swim_render.txt and each run's summary.json (tracks removed).
#
#   scripts/device/swim_render_speed.sh BUNDLE_DIR OUT_DIR
set -uo pipefail
bundle=$1
out=$2
mkdir -p "$out"
export LD_LIBRARY_PATH="$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
source "$(dirname "$0")/register_nvidia_icd.sh"
# GLVND finds NVIDIA's EGL through its vendor file; some images keep it off the default path.
if ! ls /usr/share/glvnd/egl_vendor.d/*nvidia* >/dev/null 2>&1; then
  vendor=$(find / -name '10_nvidia.json' -path '*egl_vendor.d*' -not -path '*/proc/*' 2>/dev/null | head -n 1)
  [ -n "$vendor" ] && export __EGL_VENDOR_LIBRARY_FILENAMES="$vendor"
fi
species=(--species data/blub/fish.obj:data/rigs/blub_swim.rig.json
         --species data/barramundi/BarramundiFish.gltf:data/rigs/barramundi_swim.rig.json)
summary() {  # the run's summary without the tracks
  python3 -c 'import json,sys; s=json.load(open(sys.argv[1])); s.pop("tracks",None); json.dump(s,open(sys.argv[2],"w"),indent=1)' "$1" "$2"
}
{
  date -u
  nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv 2>/dev/null
  "$bundle/bin/finflex" info
  echo "== drawn only: 1,000 fish, 1280x720, 4x multisampling, 60 frames"
  if ! "$bundle/bin/finflex" swim --fish 1000 --seconds 2 --fps 30 "${species[@]}" --render \
      --size 1280x720 --device NVIDIA; then
    echo "== the renderer failed: what EGL can find"
    ls -l /usr/share/glvnd/egl_vendor.d /usr/local/nvidia/share/glvnd/egl_vendor.d 2>&1
    find / \( -name 'libEGL_nvidia*' -o -name 'libEGL.so*' \) -not -path '*/proc/*' 2>/dev/null | head
    exit 1
  fi
  echo "== every frame a PNG: 1,000 fish, 1280x720, 30 frames"
  "$bundle/bin/finflex" swim --fish 1000 --seconds 1 --fps 30 "${species[@]}" --out /tmp/tank \
      --video none --size 1280x720 --device NVIDIA && summary /tmp/tank/summary.json "$out/summary_png.json"
  echo "== a dataset (--annotate): 1,000 fish, 1280x720, 15 frames"
  "$bundle/bin/finflex" swim --fish 1000 --seconds 0.5 --fps 30 "${species[@]}" --out /tmp/dataset \
      --video none --annotate --size 1280x720 --device NVIDIA && summary /tmp/dataset/summary.json "$out/summary_dataset.json"
  cp /tmp/tank/frames/frame_000029.png "$out/gpu_frame.png" 2>/dev/null
  for s in "$out/summary_png.json" "$out/summary_dataset.json"; do
    [ -e "$s" ] && python3 -c 'import json,sys; h=json.load(open(sys.argv[1]))["rendering"]["hand_off"]; print(sys.argv[1], "hand-off:", h["path"], "%.3f ms a frame" % (1e3 * h["seconds_per_frame_mean"]), h.get("why_not_shared", ""))' "$s"
  done
} 2>&1 | tee "$out/swim_render.txt"
