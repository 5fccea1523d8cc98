#!/usr/bin/env bash
# Sourced by the device scripts (run.sh, bundle.sh): the OpenCL and EGL set-up of a
# device machine, and the test programs that exercise device code.

# Every test program that runs kernels on the default device (test_cli runs the tool
# from its build path and is not bundled).
# shellcheck disable=SC2034 # used by the scripts that source this file
device_tests=(test_cl_deformer test_rig_deformer test_detail_levels test_level_choice test_level_deformer test_normal_format test_geometry test_spine
              test_swim test_placement)
# The hand-off's programs (the handoff suite of run.sh): the external-memory tests, the
# pictures' paths side by side, the Vulkan consumer.
# shellcheck disable=SC2034
handoff_programs=(test_gl_external test_pictures vulkan_consumer)

# Registers NVIDIA's OpenCL driver with the loader when it is installed but not
# registered (no /etc/OpenCL/vendors/nvidia.icd).
register_nvidia_icd() {
  [ -e /etc/OpenCL/vendors/nvidia.icd ] && return 0
  local driver
  driver=$(find / -name 'libnvidia-opencl.so.1' -not -path '*/proc/*' 2>/dev/null | head -n 1)
  if [ -n "$driver" ]; then
    mkdir -p /etc/OpenCL/vendors
    echo "$driver" > /etc/OpenCL/vendors/nvidia.icd
  fi
}

# Makes PoCL's ICD the only one the programs see (OCL_ICD_VENDORS for the ocl-icd
# loader, OCL_ICD_FILENAMES for the Khronos loader), so that the default device is the
# CPU even where a GPU driver is registered; and a fresh PoCL kernel cache.
use_pocl_only() {
  local icds
  icds=$(mktemp -d)
  for icd in /etc/OpenCL/vendors/*pocl*.icd; do [ -e "$icd" ] && cp "$icd" "$icds/"; done
  export OCL_ICD_VENDORS=$icds
  OCL_ICD_FILENAMES=$(cat "$icds"/*.icd 2>/dev/null | head -n 1)
  export OCL_ICD_FILENAMES
  POCL_CACHE_DIR=$(mktemp -d)
  export POCL_CACHE_DIR
}

# GLVND finds NVIDIA's EGL through its vendor file; some images keep it off the
# default path.
find_nvidia_egl() {
  ls /usr/share/glvnd/egl_vendor.d/*nvidia* >/dev/null 2>&1 && return 0
  local vendor
  vendor=$(find / -name '10_nvidia.json' -path '*egl_vendor.d*' -not -path '*/proc/*' \
    2>/dev/null | head -n 1)
  if [ -n "$vendor" ]; then export __EGL_VENDOR_LIBRARY_FILENAMES="$vendor"; fi
}

# The Vulkan loader finds NVIDIA's driver through its ICD file; some images keep it off
# the default path.
find_nvidia_vulkan() {
  ls /usr/share/vulkan/icd.d/*nvidia* /etc/vulkan/icd.d/*nvidia* >/dev/null 2>&1 && return 0
  local icd
  icd=$(find / -name 'nvidia_icd*.json' -not -path '/proc/*' 2>/dev/null | head -n 1)
  if [ -n "$icd" ]; then export VK_DRIVER_FILES="$icd" VK_ICD_FILENAMES="$icd"; fi
}

# GPU machines without the GL and Vulkan loaders (GLVND's libEGL, libGL; libvulkan):
# the Debian packages of them in DIR (.deb files, downloaded beside the bundle), unpacked
# into / once.
unpack_loaders() {
  local dir=$1 deb
  [ -d "$dir" ] || return 0
  ldconfig -p | grep -q 'libEGL.so.1 ' && return 0
  for deb in "$dir"/*.deb; do dpkg -x "$deb" /; done
  ldconfig
}
