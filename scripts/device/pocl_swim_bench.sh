#!/usr/bin/env bash
# Run on the GPU machine from the repository root with a bundle made by bundle.sh:
#   scripts/device/pocl_swim_bench.sh BUNDLE_DIR OUT_DIR
# PoCL on its CPU alone: the swim (driver, placed) and the swim rig at 1,000 fish,
# 16 threads, twice; the bend at 1 and 16 threads, twice.
B=$1; OUT=$2
export LD_LIBRARY_PATH=$PWD/$B/lib
icds=$(mktemp -d); cp /etc/OpenCL/vendors/*pocl*.icd $icds/; export OCL_ICD_VENDORS=$icds
export OCL_ICD_FILENAMES=$(cat $icds/*.icd | head -n 1) POCL_CACHE_DIR=$(mktemp -d)
run() { local t=$1; shift; POCL_MAX_PTHREAD_COUNT=$t POCL_CPU_MAX_CU_COUNT=$t $B/bin/finflex bench --mesh data/blub/fish.obj --device cpu --instances 1000 --frames 15 --json "$@"; }
for r in 1 2; do
  run 16 --rig data/rigs/blub_swim.rig.json --swim
  run 16 --rig data/rigs/blub_swim.rig.json
  run 1
  run 16
done > $OUT/pocl16_swim.jsonl 2>&1
