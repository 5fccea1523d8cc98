#!/usr/bin/env bash
# The CPU figures of docs/benchmarks.md, in one run on one machine's PoCL: what
# POCL_VECTORIZER_REMARKS says of each kernel, `finflex check` on the CPU, the kernels
# against the write-only kernel over thread counts (POCL_MAX_PTHREAD_COUNT) with the
# OpenMP baselines at the same counts (OMP_NUM_THREADS), and every case at the largest
# count for each instance count. From the repository root, with a bundle made by
# bundle.sh (bin/finflex, bin/bench_deform, lib/):
#
#   scripts/device/pocl_cpu_bench.sh BUNDLE_DIR OUT_DIR [THREADS] [INSTANCES] [FRAMES]
#   scripts/device/pocl_cpu_bench.sh .device out "1 2 4 8 16" "1000 4000" 15
#
# Only PoCL is visible to the programs (OCL_ICD_VENDORS and OCL_ICD_FILENAMES name its
# ICD alone), so the default device is the CPU even where a GPU driver is registered;
# `finflex bench` also names it (--device cpu, or FINFLEX_CPU_DEVICE). Writes to OUT_DIR:
#   info.txt       machine, PoCL, `finflex info`
#   remarks_raw.txt, remarks.txt   the vectoriser's remarks, raw and per kernel
#                                  (docs/tools/vectorizer_remarks.py)
#   cases.jsonl    at the largest thread count, per instance count: every case
#   one_run.jsonl  the same, bench_deform in one process per instance count: the
#                  write-only shapes, the bend, the fused rig and both OpenMP baselines
#   scaling.jsonl  per thread count: `finflex bench` of the bend and the rig, and the
#                  OpenMP baselines (bench_deform, JSON)
#   check.txt      `finflex check` on the CPU (the device's lanes) against the reference
#   progress.txt   when each part started
# (at most 8 files, as a device run brings back). POCL_CPU_MAX_CU_COUNT is PoCL 5's name
# for POCL_MAX_PTHREAD_COUNT: both are set.
set -uo pipefail
bundle=$1
out=$2
threads=${3:-"1 2 4 8 16"}
instance_counts=${4:-"1000 4000"}
frames=${5:-15}
mkdir -p "$out"
out=$(cd "$out" && pwd)
export LD_LIBRARY_PATH="$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export OMP_WAIT_POLICY=passive
finflex="$bundle/bin/finflex"
bench_deform="$bundle/bin/bench_deform"
fish=data/blub/fish.obj
rig=data/rigs/blub.rig.json
swim=data/rigs/blub_swim.rig.json
# bench_deform's mesh and rig (its defaults are paths of the machine it was built on).
export FINFLEX_MESH="$PWD/$fish" FINFLEX_RIG="$PWD/$rig"
largest=${threads##* }
first_instances=${instance_counts%% *}

# PoCL's ICD alone.
icds=$(mktemp -d)
for icd in /etc/OpenCL/vendors/*pocl*.icd; do [ -e "$icd" ] && cp "$icd" "$icds/"; done
export OCL_ICD_VENDORS=$icds
# The Khronos loader reads OCL_ICD_FILENAMES (library paths) instead.
OCL_ICD_FILENAMES=$(cat "$icds"/*.icd 2>/dev/null | head -n 1)
export OCL_ICD_FILENAMES
export POCL_CACHE_DIR=$(mktemp -d)

# One `finflex bench` as a JSON line with the case's name and thread count.
bench() {
  local name=$1 count=$2
  shift 2
  local result
  result=$(POCL_MAX_PTHREAD_COUNT=$count POCL_CPU_MAX_CU_COUNT=$count "$finflex" bench --mesh "$fish" --device "${FINFLEX_CPU_DEVICE:-cpu}" --json "$@") || result=null
  echo "{\"case\":\"$name\",\"threads\":$count,\"result\":$result}"
}

# bench_deform with a filter, its JSON report on one line.
bench_deform_json() {
  local name=$1 count=$2 filter=$3
  local report
  report=$(POCL_MAX_PTHREAD_COUNT=$count POCL_CPU_MAX_CU_COUNT=$count OMP_NUM_THREADS=$count \
    "$bench_deform" \
    --benchmark_filter="$filter" --benchmark_format=json 2>/dev/null |
    python3 -c 'import json,sys; print(json.dumps(json.load(sys.stdin)))') || report=null
  echo "{\"case\":\"$name\",\"threads\":$count,\"report\":$report}"
}

progress() { echo "$(date -u +%T) $*" >> "$out/progress.txt"; }
progress "start"
{
  date -u
  echo "threads: $threads; instances: $instance_counts; frames: $frames"
  nproc
  lscpu | grep -E 'Model name|^CPU\(s\)|Thread|Core|Socket|NUMA node|L1d|L2|L3|Flags' | cut -c1-200
  grep MemTotal /proc/meminfo
  (dpkg -l 2>/dev/null | grep -i pocl) || ls /usr/lib/x86_64-linux-gnu/ | grep -i pocl
  "$finflex" info
} > "$out/info.txt" 2>&1

# What the vectoriser says of each kernel: PoCL prints it when it compiles a kernel, so
# this part runs first, on the empty cache (which the timed runs then use).
progress "remarks"
remark() {
  local name=$1
  shift
  echo "== $name"
  POCL_VECTORIZER_REMARKS=1 "$finflex" bench --mesh "$fish" --instances 64 --frames 1 --json "$@"
}
{
  remark "bend paper, 1 lane" --lanes 1
  remark "bend paper, device lanes" --lanes 0
  remark "rig fused, 1 lane" --rig "$rig" --lanes 1
  remark "rig fused, device lanes" --rig "$rig" --lanes 0
  remark "rig passes, device lanes" --rig "$rig" --path passes --lanes 0
  remark "swim rig (spine) fused, 1 lane" --rig "$swim" --lanes 1
  remark "swim rig (spine) fused, device lanes" --rig "$swim" --lanes 0
} > "$out/remarks_raw.txt" 2>&1
python3 "$(dirname "$0")/../../docs/tools/vectorizer_remarks.py" "$out/remarks_raw.txt" > "$out/remarks.txt" 2>&1

# Every case at the largest thread count.
progress "cases"
for instances in $instance_counts; do
  n="--instances $instances --frames $frames"
  bench "bend paper" "$largest" $n
  bench "bend paper, plain stores" "$largest" $n --stores plain
  bench "bend paper, 8 lanes" "$largest" $n --lanes 8
  bench "bend paper, 1 lane" "$largest" $n --lanes 1
  bench "bend exact" "$largest" $n --mode exact
  bench "rig fused" "$largest" $n --rig "$rig"
  bench "rig fused, 1 lane" "$largest" $n --rig "$rig" --lanes 1
  bench "rig passes" "$largest" $n --rig "$rig" --path passes
  bench "swim rig (spine) fused" "$largest" $n --rig "$swim"
  bench "swim rig (spine) fused, 1 lane" "$largest" $n --rig "$swim" --lanes 1
done > "$out/cases.jsonl"
progress "one run"
for instances in $instance_counts; do
  bench_deform_json "one process" "$largest" \
    "^BM_(WriteOnly/float32(_4_per_item|_lanes|_lanes_plain)?|Bend/paper_rotate|Rig/fused|OpenMP(Simd)?Baseline)/$instances/"
done > "$out/one_run.jsonl"

# Scaling with threads.
progress "scaling"
for count in $threads; do
  bench "bend paper" "$count" --instances "$first_instances" --frames "$frames"
  bench "rig fused" "$count" --instances "$first_instances" --frames "$frames" --rig "$rig"
  bench_deform_json "OpenMP baselines" "$count" "^BM_OpenMP(Simd)?Baseline/$first_instances/"
done > "$out/scaling.jsonl"

# The device against the double reference, with the device's lanes.
progress "check"
{
  "$finflex" check --in "$fish"
  "$finflex" check --in data/barramundi/BarramundiFish.gltf
  "$finflex" check --in "$fish" --rig "$rig"
  "$finflex" check --in "$fish" --rig "$swim"
} > "$out/check.txt" 2>&1
progress "done"
echo "wrote $out"
