#!/usr/bin/env bash
# Packs what a run on a GPU machine without this project's build dependencies needs:
# the tool, the benchmarks, the tests that exercise device code, and the shared
# libraries they load that such a machine may lack (OpenMesh, tinygltf, stb, Google
# Benchmark; libepoxy and the X11 client libraries GLVND's libGL loads, for the renderer;
# the Vulkan loader, which the external-memory hand-off opens),
# into DIR/bin and DIR/lib. The OpenCL loader stays the machine's.
#
#   scripts/device/bundle.sh BUILD_DIR DIR [EXTRA_BINARY ...]
set -euo pipefail
build=$1
out=$2
shift 2
rm -rf "$out"
mkdir -p "$out/bin" "$out/lib"
# shellcheck source=scripts/device/opencl_env.sh
source "$(dirname "$0")/opencl_env.sh"
binaries=("$build/apps/finflex" "$build/bench/bench_deform")
for test in "${device_tests[@]}"; do
  if [ ! -f "$build/tests/$test" ]; then
    echo "bundle.sh: $build/tests/$test is missing (build the tests first)" >&2
    exit 1
  fi
  binaries+=("$build/tests/$test")
done
for program in "${handoff_programs[@]}"; do
  found=$(find "$build/tests" "$build/examples" -name "$program" -type f 2>/dev/null | head -n 1)
  if [ -z "$found" ]; then
    echo "bundle.sh: $program is missing under $build (build the tests and examples first)" >&2
    exit 1
  fi
  binaries+=("$found")
done
binaries+=("$@")
for binary in "${binaries[@]}"; do
  [ -f "$binary" ] && cp "$binary" "$out/bin/"
done
for binary in "$out"/bin/*; do
  ldd "$binary" | awk '/=> \//{print $3}' |
    grep -E 'libOpenMesh|libtinygltf|libmeshoptimizer|libstb|libbenchmark|libgomp|libepoxy' | xargs -r -I{} cp -L {} "$out/lib/"
done
for library in libX11.so.6 libxcb.so.1 libXau.so.6 libXdmcp.so.6 libbsd.so.0 libmd.so.0 \
  libvulkan.so.1; do
  # awk stops at the first match, which may end ldconfig with SIGPIPE: not a failure.
  found=$(ldconfig -p | awk -v name="$library" '$1 == name && /x86-64/ {print $NF; exit}' || true)
  if [ -n "$found" ]; then cp -L "$found" "$out/lib/"; fi
done
du -sh "$out"
