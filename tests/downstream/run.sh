#!/usr/bin/env bash
# Installs the FinFlex build tree into a scratch prefix, then configures, builds and
# runs the downstream project against it, as a user linking the library would.
# The downstream project is built with FinFlex's C++ compiler and, in a sanitizer
# build (FINFLEX_SANITIZE), with the same -fsanitize flags.
# Usage: run.sh FINFLEX_BUILD_DIR SCRATCH_DIR [CXX_COMPILER [SANITIZERS]]
set -euo pipefail
build_dir=$1
scratch=$2
compiler=${3:-}
sanitize=${4:-}
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$scratch"
cmake --install "$build_dir" --prefix "$scratch/prefix" >/dev/null
options=(-DCMAKE_PREFIX_PATH="$scratch/prefix" -DCMAKE_BUILD_TYPE=Release)
[ -z "$compiler" ] || options+=(-DCMAKE_CXX_COMPILER="$compiler")
if [ -n "$sanitize" ]; then
  options+=("-DCMAKE_CXX_FLAGS=-fsanitize=$sanitize -fno-sanitize-recover=all -fno-omit-frame-pointer"
            "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=$sanitize")
fi
cmake -S "$here" -B "$scratch/build" "${options[@]}" >/dev/null
cmake --build "$scratch/build" >/dev/null
"$scratch/build/downstream"
"$scratch/build/downstream_c"
echo "downstream: the C++ and C programs agree with the reference"
