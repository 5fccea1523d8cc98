#!/usr/bin/env bash
# Run on a GPU machine from the repository root with a bundle made by bundle.sh:
# registers the NVIDIA OpenCL driver when it is installed but not registered, lists
# the devices, runs every test program that exercises device code on the default
# device (the first GPU) and `finflex check` on the GPU. Writes everything to
# OUT_DIR/gpu_checks.txt (and stdout); exits 1 when a test or a check fails.
#
#   scripts/device/gpu_checks.sh BUNDLE_DIR OUT_DIR [DEVICE]
#
# What only a GPU runs by default, and where it is tested:
#  - half normals stored with vstore_half (FF_GPU=1): every half-normal test of
#    test_normal_format, and test_rig_deformer's HeterogeneousFrameEqualsSeparateRuns;
#  - 2 (float32) or 4 (half normals, rigs) instances per work-item: every test of
#    test_cl_deformer, test_rig_deformer, test_normal_format and test_geometry;
#  - RigDispatch::kPerComponent: every rig test;
#  - the hardware's sine and cosine in the spine (FF_NATIVE_TRIG, NVIDIA's GPUs):
#    test_spine and test_swim against the double-precision reference, and
#    `finflex check` of the swim rig.
# CPUs run these too where they can be forced: the work-item shapes and the dispatch
# through ClOptions (SeveralInstancesPerWorkItemGiveTheSameResult in test_cl_deformer
# and test_rig_deformer, the rig tests of both dispatches, HalfNormalsInTheShapesGpusTake),
# vstore_half in a kernel of the test's own (EveryHalfStoreWritesTheNearestHalf).
set -uo pipefail
bundle=$1
out=$2
device=${3:-NVIDIA}
mkdir -p "$out"
log="$out/gpu_checks.txt"
export LD_LIBRARY_PATH="$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export FINFLEX_DATA_DIR="$PWD/data" POCL_CACHE_DIR=/tmp/pocl-cache
source "$(dirname "$0")/register_nvidia_icd.sh"
failed=()
{
  date -u
  nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv 2>/dev/null
  "$bundle/bin/finflex" info
  for test in "$bundle"/bin/test_*; do
    name=$(basename "$test")
    echo "== $name on the default device (the first GPU)"
    # --gtest_brief: every failure in full, then the summary.
    if ! "$test" --gtest_brief=1 2>&1; then failed+=("$name"); fi
  done
  for mesh in data/blub/fish.obj data/barramundi/BarramundiFish.gltf; do
    echo "== finflex check --in $mesh --device $device"
    if ! "$bundle/bin/finflex" check --in "$mesh" --device "$device"; then
      failed+=("check $mesh")
    fi
  done
  for rig in data/rigs/blub.rig.json data/rigs/blub_swim.rig.json; do
    echo "== finflex check --rig $rig --device $device"
    if ! "$bundle/bin/finflex" check --in data/blub/fish.obj --rig "$rig" --device "$device"; then
      failed+=("check --rig $rig")
    fi
  done
  if [ ${#failed[@]} -eq 0 ]; then
    echo "== all passed"
  else
    echo "== FAILED: ${failed[*]}"
  fi
} 2>&1 | tee "$log"
grep -q '^== all passed$' "$log"
