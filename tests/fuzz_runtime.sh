#!/usr/bin/env bash
# Runs the rig and command-line fuzzers (tests/fuzz_rig/, tests/fuzz_cli/) of a build
# configured with -DFINFLEX_FUZZ=ON (clang, usually with
# -DFINFLEX_SANITIZE=address,undefined), each for SECONDS, from the repository root
# (the command-line seeds name data/ files), with a 2 GB memory limit (allocating more
# is a finding) and 10 s per input. New inputs go to WORK_DIR/<target>-corpus, crashes
# to WORK_DIR/<target>-crashes/; a crash makes the exit status non-zero after all
# targets ran. Prints one summary line per target: executions, corpus, crashes.
# Usage: tests/fuzz_runtime.sh BUILD_DIR SECONDS [WORK_DIR]
set -uo pipefail
build=$(cd "$1" && pwd)
seconds=$2
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
work=${3:-$build/fuzz-runtime}
mkdir -p "$work"
work=$(cd "$work" && pwd)
cd "$root"

status=0
run() {
  local name=$1 binary=$2 dict=$3
  shift 3
  local corpus="$work/$name-corpus" crashes="$work/$name-crashes"
  mkdir -p "$corpus" "$crashes"
  local log="$work/$name.log"
  local options=(-max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -max_len=65536
    -artifact_prefix="$crashes/" -print_final_stats=1)
  [ "$dict" = "-" ] || options+=(-dict="$dict")
  "$binary" "${options[@]}" "$corpus" "$@" >"$log" 2>&1
  local rc=$?
  local runs corpus_size found
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
  corpus_size=$(find "$corpus" -type f | wc -l)
  found=$(find "$crashes" -type f | wc -l)
  echo "fuzz $name: ${runs:-0} executions in ${seconds} s, corpus $corpus_size inputs, $found crashes (exit $rc)"
  if [ "$rc" -ne 0 ] || [ "$found" -ne 0 ]; then
    status=1
    tail -n 40 "$log"
  fi
}

run fuzz_rig_json "$build/tests/fuzz_rig/fuzz_rig_json" "$here/fuzz_rig/rig.dict" \
  "$here/fuzz_rig/corpus" "$root/data/rigs"
run fuzz_rig_tree "$build/tests/fuzz_rig/fuzz_rig_tree" -
run fuzz_cli "$build/tests/fuzz_cli/fuzz_cli" "$here/fuzz_cli/cli.dict" "$here/fuzz_cli/corpus"
exit $status
