#!/usr/bin/env bash
# Installs the FinFlex build tree into a scratch prefix, then configures, builds and
# runs the downstream project against it, as a user linking the library would.
# Usage: run.sh FINFLEX_BUILD_DIR SCRATCH_DIR
set -euo pipefail
build_dir=$1
scratch=$2
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$scratch"
cmake --install "$build_dir" --prefix "$scratch/prefix" >/dev/null
cmake -S "$here" -B "$scratch/build" -DCMAKE_PREFIX_PATH="$scratch/prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$scratch/build" >/dev/null
"$scratch/build/downstream"
"$scratch/build/downstream_c"
echo "downstream: the C++ and C programs agree with the reference"
