#!/usr/bin/env bash
# Builds the mesh-reader fuzz harnesses with clang (libFuzzer, AddressSanitizer,
# UndefinedBehaviorSanitizer) and runs each for a bounded time.
#
#   tests/fuzz/run.sh [SECONDS] [TARGET...]
#
# SECONDS: time per target (default 60). TARGET: obj ply off stl gltf glb (default:
# all, one after the other). Each run starts from tests/fuzz/corpus/<target>/ plus
# what earlier runs found (kept in the build folder, never in the source tree), with
# tests/fuzz/dict/<target>.dict, a 2 GB memory limit and a 10 s limit per input.
# Exits non-zero if any target found a crash, a sanitizer report, a timeout, an
# out-of-memory or a broken contract; the input is saved as
# <build>/findings/<target>/crash-* (or timeout-*, oom-*) and the run continues
# with the next target. The build folder is build-fuzz/ in the project root, or
# $FINFLEX_FUZZ_BUILD (configured here when it is not yet).
set -euo pipefail

seconds="${1:-60}"
if [[ $# -gt 0 ]]; then shift; fi
targets=("$@")
if [[ ${#targets[@]} -eq 0 ]]; then targets=(obj ply off stl gltf glb); fi
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || [[ "$seconds" -eq 0 ]]; then
  echo "usage: $0 [SECONDS] [obj|ply|off|stl|gltf|glb ...]" >&2
  exit 2
fi

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="${FINFLEX_FUZZ_BUILD:-$root/build-fuzz}"

# Longest input per target: room for the seeds (the control-mesh OBJ has 9 kB).
max_len() {
  case "$1" in
    obj) echo 16384 ;;
    gltf | glb) echo 8192 ;;
    *) echo 4096 ;;
  esac
}

for target in "${targets[@]}"; do
  if [[ ! -d "$here/corpus/$target" ]]; then
    echo "unknown target '$target' (obj ply off stl gltf glb)" >&2
    exit 2
  fi
done

# A build folder configured already (with FINFLEX_FUZZ=ON: CI's sanitized build) is
# used as it is; otherwise one with only the harnesses is configured.
if [[ ! -f "$build/CMakeCache.txt" ]]; then
  cmake -S "$root" -B "$build" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFINFLEX_FUZZ=ON -DFINFLEX_BUILD_TESTS=OFF \
    -DFINFLEX_BUILD_APPS=OFF -DFINFLEX_BUILD_BENCH=OFF >/dev/null
fi
cmake --build "$build" -j"$(nproc)" --target "${targets[@]/#/fuzz_}"

failed=()
for target in "${targets[@]}"; do
  corpus="$build/corpus/$target"
  findings="$build/findings/$target"
  mkdir -p "$corpus" "$findings"
  echo "== fuzz_$target: $seconds s"
  if ! "$build/tests/fuzz/fuzz_$target" "$corpus" "$here/corpus/$target" \
    -dict="$here/dict/$target.dict" -max_len="$(max_len "$target")" \
    -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
    -artifact_prefix="$findings/" -print_final_stats=1 2>"$build/fuzz_$target.log"; then
    failed+=("$target")
    echo "fuzz_$target found a problem: $(ls -t "$findings" | head -n 1) (log: $build/fuzz_$target.log)"
  fi
  grep -E "^stat::number_of_executed_units|^Done [0-9]+ runs" "$build/fuzz_$target.log" || true
done

if [[ ${#failed[@]} -gt 0 ]]; then
  echo "findings in: ${failed[*]}" >&2
  exit 1
fi
echo "no findings"
