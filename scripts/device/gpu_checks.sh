#!/usr/bin/env bash
# Run on a GPU machine from the repository root with a bundle made by bundle.sh:
# registers the NVIDIA OpenCL driver when it is installed but not registered, lists
# the devices, and runs the tests that exercise device code and `finflex check` on
# the GPU. Writes everything to OUT_DIR/gpu_checks.txt (and stdout).
#
#   scripts/device/gpu_checks.sh BUNDLE_DIR OUT_DIR [DEVICE]
set -uo pipefail
bundle=$1
out=$2
device=${3:-NVIDIA}
mkdir -p "$out"
log="$out/gpu_checks.txt"
export LD_LIBRARY_PATH="$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export FINFLEX_DATA_DIR="$PWD/data" POCL_CACHE_DIR=/tmp/pocl-cache
if [ ! -e /etc/OpenCL/vendors/nvidia.icd ]; then
  driver=$(find / -name 'libnvidia-opencl.so.1' -not -path '*/proc/*' 2>/dev/null | head -n 1)
  if [ -n "$driver" ]; then
    mkdir -p /etc/OpenCL/vendors
    echo "$driver" > /etc/OpenCL/vendors/nvidia.icd
  fi
fi
{
  date -u
  nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv 2>/dev/null
  "$bundle/bin/finflex" info
  for test in "$bundle"/bin/test_*; do
    echo "== $(basename "$test") on the default device (the first GPU)"
    "$test" --gtest_brief=1 2>&1 | tail -n 4
  done
  for mesh in data/blub/fish.obj data/barramundi/BarramundiFish.gltf; do
    echo "== finflex check --in $mesh --device $device"
    "$bundle/bin/finflex" check --in "$mesh" --device "$device"
  done
  echo "== finflex check --rig data/rigs/blub.rig.json --device $device"
  "$bundle/bin/finflex" check --in data/blub/fish.obj --rig data/rigs/blub.rig.json --device "$device"
} 2>&1 | tee "$log"
