#!/usr/bin/env bash
# Sourced by the device scripts: registers NVIDIA's OpenCL driver with the loader when
# it is installed but not registered (no /etc/OpenCL/vendors/nvidia.icd).
if [ ! -e /etc/OpenCL/vendors/nvidia.icd ]; then
  nvidia_driver=$(find / -name 'libnvidia-opencl.so.1' -not -path '*/proc/*' 2>/dev/null | head -n 1)
  if [ -n "$nvidia_driver" ]; then
    mkdir -p /etc/OpenCL/vendors
    echo "$nvidia_driver" > /etc/OpenCL/vendors/nvidia.icd
  fi
fi
