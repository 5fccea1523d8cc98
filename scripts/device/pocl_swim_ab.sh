#!/usr/bin/env bash
# Run on the GPU machine from the repository root with a bundle made by bundle.sh:
#   scripts/device/pocl_swim_ab.sh BUNDLE_DIR OUT_FILE BINARY[|OPTIONS[|ENVIRONMENT]] ...
# PoCL on its CPU: the swim of 1,000 fish (driver, placed deformation) with 2 and 16
# threads (THREADS, default "2 16"), each binary in turn, ROUNDS rounds (default 3), so
# that builds are compared side by side on the same machine; OPTIONS, bench options
# for that entry (e.g. "bin/finflex|--dispatch per-component"); ENVIRONMENT, variables
# for its runs (e.g. "bin/finflex||GLIBC_TUNABLES=glibc.malloc.hugetlb=1"). MODE (default swim):
# swim; rig, the swim rig's deformation without the driver; bend, the whole-body bend.
# One JSON line per run: {"binary" (the binary's name, its options and environment),
# "mode", "threads", "round", "result"}.
set -uo pipefail
bundle=$1
out=$2
shift 2
export LD_LIBRARY_PATH=$PWD/$bundle/lib
icds=$(mktemp -d)
cp /etc/OpenCL/vendors/*pocl*.icd "$icds"/
export OCL_ICD_VENDORS=$icds
export OCL_ICD_FILENAMES=$(cat "$icds"/*.icd | head -n 1) POCL_CACHE_DIR=$(mktemp -d)
mode=${MODE:-swim}
case $mode in
  swim) mode_options=(--rig data/rigs/blub_swim.rig.json --swim) ;;
  rig) mode_options=(--rig data/rigs/blub_swim.rig.json) ;;
  bend) mode_options=() ;;
  *) echo "MODE: '$mode' is not swim, rig or bend" >&2; exit 2 ;;
esac
: > "$out"
for round in $(seq "${ROUNDS:-3}"); do
  for threads in ${THREADS:-2 16}; do
    for entry in "$@"; do
      binary=${entry%%|*}
      options=""
      environment=""
      [[ $entry == *"|"* ]] && options=${entry#*|}
      if [[ $options == *"|"* ]]; then
        environment=${options#*|}
        options=${options%%|*}
      fi
      # shellcheck disable=SC2086 # the options and the environment are words
      result=$(env $environment POCL_MAX_PTHREAD_COUNT=$threads POCL_CPU_MAX_CU_COUNT=$threads "$binary" bench \
        --mesh data/blub/fish.obj "${mode_options[@]}" --device cpu \
        --instances 1000 --frames 30 --json $options) || result=null
      echo "{\"binary\": \"$(basename "$binary")${options:+ $options}${environment:+ $environment}\", \"mode\": \"$mode\", \"threads\": $threads, \"round\": $round, \"result\": $result}" >> "$out"
    done
  done
done
