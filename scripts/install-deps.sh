#!/usr/bin/env bash
# Installs FinFlex's build, test and run-time dependencies from Debian 12 packages, and
# the Python packages the dataset test reads COCO files with (pycocotools, Pillow, numpy:
# tests/python/requirements.txt) into a virtual environment, .venv in the repository.
# Idempotent: what is already present is left as it is.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  pocl-opencl-icd ocl-icd-opencl-dev opencl-c-headers opencl-clhpp-headers clinfo
  libglm-dev libopenmesh-dev libtinygltf-dev nlohmann-json3-dev libcli11-dev libstb-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libegl-dev libgles-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri libepoxy-dev zlib1g-dev ffmpeg
  python3 python3-venv
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
else
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
  echo "install-deps: installed ${missing[*]}"
fi

# PyPI packages, through pip, in the repository's own virtual environment.
root="$(cd "$(dirname "$0")/.." && pwd)"
venv="$root/.venv"
requirements="$root/tests/python/requirements.txt"
if "$venv/bin/python" -c 'import pycocotools, PIL, numpy' 2>/dev/null; then
  echo "install-deps: $venv has the Python packages"
else
  python3 -m venv "$venv"
  "$venv/bin/python" -m pip install -q --disable-pip-version-check -r "$requirements"
  echo "install-deps: installed the packages of $requirements into $venv"
fi
