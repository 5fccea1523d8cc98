#!/usr/bin/env bash
# Installs FinFlex's build, test and run-time dependencies from Debian 12 packages;
# the Python build tools Debian 12 does not package (nanobind, scikit-build-core) from
# PyPI with pip into the `python3` found on PATH (Debian's own on a fresh machine:
# `pip install --break-system-packages`, as root or with sudo); and the Python packages
# the dataset test reads COCO files with (pycocotools, Pillow, numpy:
# tests/python/requirements.txt) into a virtual environment, .venv in the repository.
# Idempotent: what is already present is left as it is.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  pocl-opencl-icd ocl-icd-opencl-dev opencl-c-headers opencl-clhpp-headers clinfo
  libglm-dev libopenmesh-dev libtinygltf-dev libmeshoptimizer-dev nlohmann-json3-dev libcli11-dev libstb-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libegl-dev libgles-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri libepoxy-dev zlib1g-dev ffmpeg
  libvulkan-dev libvulkan-volk-dev glslang-tools  # the external-memory hand-off (FinFlex::vulkan)
  mesa-vulkan-drivers  # lavapipe: Vulkan on the CPU, whose memory llvmpipe and PoCL share
  python3 python3-dev python3-pip python3-venv python3-numpy python3-pytest python3-pyopencl
  clang libclang-rt-14-dev  # libFuzzer and clang's sanitizers (CI's fuzzing step)
  clang-format  # CI's format check (scripts/check-format.sh)
  ninja-build  # CI's builds (CMAKE_GENERATOR=Ninja: .ci/run)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} Debian packages present"
else
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
  echo "install-deps: installed ${missing[*]}"
fi

# Python modules for the bindings (bindings/python) and their tests. Debian's python3
# gets numpy and pytest from the packages above; another python3 first on PATH (a
# pyenv or a virtual environment) gets them from PyPI too.
python_modules=(nanobind:nanobind scikit_build_core:scikit-build-core numpy:numpy pytest:pytest)
python_missing=()
for entry in "${python_modules[@]}"; do
  python3 -c "import ${entry%%:*}" 2>/dev/null || python_missing+=("${entry#*:}")
done
if [ ${#python_missing[@]} -eq 0 ]; then
  echo "install-deps: Python modules present for $(python3 -c 'import sys; print(sys.executable)')"
else
  pip_root=()
  python3 -c 'import sys; sys.exit(sys.prefix.startswith("/usr"))' || pip_root=("${sudo_cmd[@]}")
  "${pip_root[@]}" python3 -m pip install -q --root-user-action=ignore --break-system-packages "${python_missing[@]}"
  echo "install-deps: pip installed ${python_missing[*]}"
fi

# PyPI packages of the dataset test, through pip, in the repository's own virtual
# environment.
root="$(cd "$(dirname "$0")/.." && pwd)"
venv="$root/.venv"
requirements="$root/tests/python/requirements.txt"
if "$venv/bin/python" -c 'import pycocotools, PIL, numpy, pytest, ray' 2>/dev/null; then
  echo "install-deps: $venv has the Python packages"
else
  python3 -m venv "$venv"
  "$venv/bin/python" -m pip install -q --disable-pip-version-check -r "$requirements"
  echo "install-deps: installed the packages of $requirements into $venv"
fi
