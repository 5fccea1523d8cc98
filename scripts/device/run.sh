#!/usr/bin/env bash
# The device runner: suites of measurements and checks on one machine, N rounds, on one
# build or as an A/B of two builds or two option sets (the sides' runs interleaved, so
# that a busy machine slows both alike), then one table (bench_table.py). From the
# repository root, with a build tree or a bundle made by bundle.sh:
#
#   scripts/device/run.sh [OPTIONS] SUITE...
#   scripts/device/run.sh --build .device --device h200 gpu_checks swim_bench finflex_bench
#   scripts/device/run.sh --build old --b new --rounds 3 --out /tmp/ab finflex_bench
#   scripts/device/run.sh --cpu --threads "2 16" --b-env GLIBC_TUNABLES=glibc.malloc.hugetlb=1 \
#     --rounds 3 --out /tmp/ab pocl
#   scripts/device/run.sh --cpu --instances 50 --frames 5 --out /tmp/try finflex_bench pocl
#
# Options:
#   --build DIR          side A (and the only side without A/B): a build tree
#                        (DIR/apps/finflex) or a bundle (DIR/bin/finflex, DIR/lib); default build
#   --b DIR              A/B of builds: side B runs DIR's programs
#   --a-options, --b-options "OPTIONS"   A/B of options: `finflex bench` options of a side
#   --a-env, --b-env "VAR=VALUE ..."     A/B of environments: variables of a side's runs
#   --rounds N           every case N times (default 1; the docs' tables: 3)
#   --device NAME        results in docs/results/NAME/ (h200, h100, xeon-16-core, vm-2-core)
#   --out DIR            results in DIR instead
#   --cpu                PoCL alone (its ICD the only one visible: its CPU the default device)
#   --threads "N ..."    with --cpu: PoCL's thread counts, each a round of every case
#                        (POCL_MAX_PTHREAD_COUNT, OMP_NUM_THREADS; default: the machine's cores)
#   --cl-device NAME     the OpenCL device, `finflex --device` (default NVIDIA; with --cpu
#                        the default device)
#   --instances "N ..."  the benches' instance counts instead of the suite's
#   --frames N           the benches' timed frames instead of the suite's
#   --cases REGEX        only the `finflex bench` cases whose names match (grep -E)
#   --filter REGEX       bench_deform: --benchmark_filter
#   --dry-run            print every command instead of running it
#
# Suites, each written to OUT/SUITE.EXT (JSONL: one line a run, {"suite", "case",
# "side", "round", "threads", "result"}, `finflex bench --json` as the result, null
# when it failed):
#   gpu_checks     .txt    the device tests (opencl_env.sh device_tests) on the default
#                          device, `finflex check` of the bundled fish and rigs on the GPU;
#                          the run exits 1 when one fails
#   cpu_checks     .txt    `finflex check` of the same on the CPU
#   finflex_bench  .jsonl  the standard cases at 4,000 fish (GPUs) or 1,000 (CPUs): the
#                          bend (paper, half normals, exact), the Blub rig (fused, passes),
#                          the swim rig (no driver), the swim; on CPUs also plain stores
#                          and 1 and 8 lanes
#   swim_bench     .jsonl  the swim of 10,000 fish: float32, the tank stepping in the
#                          frame loop, half and Jacobian normals, 2 and 4 instances per
#                          work-item; the swim rig alone and the bend at the same count
#   farm           .jsonl  `finflex bench --farm`: 100,000 fish in a hall of 16 tanks
#                          (GPUs; 2,000 on CPUs) with levels of detail at 1 pixel (with
#                          and without the walls' occlusion) and 2 pixels, half normals
#                          and 4 coarser levels, each beside the same hall at full detail
#   layouts        .jsonl  the hand-off's output layouts (docs/handoff.md), bend and rig,
#                          slot and mesh order, previous positions, half interleaved
#   sweep          .jsonl  instances 1 to 4,000 x the bundled meshes and a 112,642-vertex
#                          one x bend modes, rigs, half normals
#   pocl           .jsonl  PoCL per thread count: the bend, the swim rig, the swim, the
#                          Blub rig at 1,000 fish, and the OpenMP baselines (bench_deform)
#   bench_deform   .txt    the Google Benchmark program (with --cpu: per thread count)
#   render_speed   .txt    `finflex swim` with rendering on the GPU (EGL, no display):
#                          drawn only, every frame a PNG, a dataset; each on the
#                          external-memory path and the copy path side by side
#   render_levels  .txt    `finflex swim` drawn at 1920 x 1080 on the GPU with levels of
#                          detail (--levels 4, 8) beside full detail: 1,000 fish drawn
#                          only and with a PNG a frame, 10,000 drawn only; the farm
#                          (100,000 fish in 16 tanks, --levels 6 and 8, 8 without the
#                          walls' occlusion, and 8 at a 2-pixel budget) beside full
#                          detail, and the farm's last frame (render_levels_farm.png)
#   dataset        .txt    `finflex swim --annotate` of 1,000 fish at 1280 x 720 on the GPU:
#                          mono COCO; with YOLO and depth; a stereo pair; and with a
#                          lens and noise; mono with refraction and varied optics; the
#                          underwater camera straight and behind its port (frame times
#                          side by side)
#   dataset_scaling .txt   `python -m finflex.dataset` by workers (bench/dataset_scaling.py):
#                          400 frames of 1,000 fish at 1280 x 720 in shards of 100 on
#                          the GPU worker in process and as a Ray actor; the README's
#                          tank (200 fish, 640 x 360) on 1, 2, 4 and 8 CPU workers of
#                          the same cores each where PoCL is installed, the GPU alone
#                          and both; Ray from RAY_SITE (a folder holding it, when
#                          python3 has none)
#   level_choice   .txt    levels of detail: `finflex check --levels 4` of the bundled
#                          fish's swim rigs, and the level choice of 1,000 to 100,000
#                          fish (bench_deform's BM_LevelChoice)
#   handoff        .txt    the hand-off's checks: the external-memory tests, every
#                          path's pictures byte for byte, the Vulkan consumer, and
#                          `finflex swim` frames of the external and copy paths compared
#   remarks        .txt    PoCL's vectoriser remarks per kernel (run it first: it
#                          compiles on an empty cache)
# and OUT/info.txt: the machine, the devices.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=scripts/device/opencl_env.sh
source "$here/opencl_env.sh"

usage() {
  sed -n '2,/^set -uo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'
  exit 2
}

build=build
build_b=""
options_a=""
options_b=""
env_a=""
env_b=""
rounds=1
out=""
cpu=0
threads=""
cl_device=""
instances=""
frames=""
filter=""
case_filter=""
dry=0
suites=()
while [ $# -gt 0 ]; do
  case $1 in
    --build) build=$2; shift 2 ;;
    --b) build_b=$2; shift 2 ;;
    --a-options) options_a=$2; shift 2 ;;
    --b-options) options_b=$2; shift 2 ;;
    --a-env) env_a=$2; shift 2 ;;
    --b-env) env_b=$2; shift 2 ;;
    --rounds) rounds=$2; shift 2 ;;
    --device) out=docs/results/$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --cpu) cpu=1; shift ;;
    --threads) threads=$2; shift 2 ;;
    --cl-device) cl_device=$2; shift 2 ;;
    --instances) instances=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --filter) filter=$2; shift 2 ;;
    --cases) case_filter=$2; shift 2 ;;
    --dry-run) dry=1; shift ;;
    -h | --help) usage ;;
    -*) echo "run.sh: unknown option '$1'" >&2; usage ;;
    *) suites+=("$1"); shift ;;
  esac
done
[ ${#suites[@]} -gt 0 ] || usage
[ -n "$out" ] || { echo "run.sh: give --device NAME or --out DIR" >&2; exit 2; }
[[ $rounds =~ ^[1-9][0-9]*$ ]] || { echo "run.sh: --rounds '$rounds' is not a count" >&2; exit 2; }

sides=(A)
[ -n "$build_b$options_b$env_b" ] && sides=(A B)
[ -n "$build_b" ] || build_b=$build
# The thread counts: with --cpu PoCL's, else the device's own ("-").
[ $cpu = 1 ] || cl_device=${cl_device:-NVIDIA}
device_option=()
[ -z "$cl_device" ] || device_option=(--device "$cl_device")
if [ $cpu = 1 ]; then
  [ -n "$threads" ] || threads=$(nproc)
else
  threads=-
fi
if [ $dry = 1 ]; then
  echo "(dry run: the OpenCL set-up of opencl_env.sh is not done)" >&2
elif [ $cpu = 1 ]; then
  use_pocl_only
else
  register_nvidia_icd
fi
export FINFLEX_MESH="$PWD/data/blub/fish.obj" FINFLEX_RIG="$PWD/data/rigs/blub.rig.json"
export OMP_WAIT_POLICY=passive
export POCL_CACHE_DIR=${POCL_CACHE_DIR:-/tmp/pocl-cache}
[ $dry = 1 ] || mkdir -p "$out"
failed=()

# A side's build folder, its program NAME (finflex, bench_deform, test_*), its options
# and its environment.
side_build() { if [ "$1" = B ]; then echo "$build_b"; else echo "$build"; fi; }
program() {
  local dir
  dir=$(side_build "$1")
  case $2 in
    finflex) [ -e "$dir/bin/finflex" ] && echo "$dir/bin/finflex" || echo "$dir/apps/finflex" ;;
    bench_deform)
      [ -e "$dir/bin/bench_deform" ] && echo "$dir/bin/bench_deform" ||
        echo "$dir/bench/bench_deform" ;;
    *) [ -e "$dir/bin/$2" ] && echo "$dir/bin/$2" || echo "$dir/tests/$2" ;;
  esac
}
side_options() { if [ "$1" = B ]; then echo "$options_b"; else echo "$options_a"; fi; }
# The environment of a side's run with `threads` PoCL threads.
side_env() {
  local dir count=$2
  dir=$(side_build "$1")
  [ -d "$dir/lib" ] && echo "LD_LIBRARY_PATH=$dir/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  [ "$count" != - ] && echo "POCL_MAX_PTHREAD_COUNT=$count POCL_CPU_MAX_CU_COUNT=$count OMP_NUM_THREADS=$count"
  if [ "$1" = B ]; then echo "$env_b"; else echo "$env_a"; fi
}
# The side's label in the table: its build, options and environment where they differ.
side_label() {
  [ ${#sides[@]} = 1 ] && return
  local label=$1
  [ "$build_b" != "$build" ] && label+=" $(side_build "$1")"
  local o e
  o=$(side_options "$1")
  if [ "$1" = B ]; then e=$env_b; else e=$env_a; fi
  echo "$label${o:+ $o}${e:+ $e}"
}

# Runs a command (printed instead with --dry-run): env VAR=VALUE ... PROGRAM ARGS.
run() {
  if [ $dry = 1 ]; then
    printf '%q ' "$@" >&2
    echo >&2
    return 0
  fi
  "$@"
}

json_string() { python3 -c 'import json,sys; print(json.dumps(sys.argv[1]))' "$1"; }

# One `finflex bench --json` run of a case as a JSON line in FILE. Options without
# --mesh run on the bundled Blub; without --instances, on each count of `counts`.
bench_line() {
  local file=$1 round=$2 count=$3 side=$4 name=$5 case_options=$6 number=$7
  local -a words
  # shellcheck disable=SC2206,SC2207 # the options and the environment are words
  words=(env $(side_env "$side" "$count") "$(program "$side" finflex)" bench)
  [[ " $case_options " == *" --mesh "* ]] || words+=(--mesh data/blub/fish.obj)
  [[ " $case_options " == *" --instances "* ]] || words+=(--instances "$number")
  [[ " $case_options " == *" --frames "* ]] || words+=(--frames "$suite_frames")
  # shellcheck disable=SC2206,SC2207
  words+=("${device_option[@]}" --json $case_options $(side_options "$side"))
  local result
  if [ $dry = 1 ]; then
    run "${words[@]}"
    return
  fi
  result=$("${words[@]}") || result=null
  [ -n "$result" ] || result=null
  local label
  label=$(side_label "$side")
  echo "{\"suite\": \"$suite\", \"case\": $(json_string "$name"), \"side\": $(json_string "$label"), \"round\": $round, \"threads\": ${count/-/null}, \"result\": $result}" >> "$file"
}

# Every case ("NAME|OPTIONS") of a JSONL suite: rounds, then thread counts, then
# instance counts, then cases, then sides, innermost.
bench_suite() {
  local file="$out/$suite.jsonl" round count number spec side
  [ $dry = 1 ] || : > "$file"
  for round in $(seq "$rounds"); do
    for count in $threads; do
      for number in $suite_instances; do
        for spec in "$@"; do
          if [ -n "$case_filter" ] && ! grep -qE -- "$case_filter" <<< "${spec%%|*}"; then
            continue
          fi
          for side in "${sides[@]}"; do
            bench_line "$file" "$round" "$count" "$side" "${spec%%|*}" "${spec#*|}" "$number"
          done
        done
      done
    done
  done
}

# bench_deform with FILTER at `count` threads, its JSON report on one line in FILE.
baselines_line() {
  local file=$1 round=$2 count=$3 side=$4 name=$5 benchmark_filter=$6
  local -a words
  # shellcheck disable=SC2206,SC2207
  words=(env $(side_env "$side" "$count") "$(program "$side" bench_deform)"
    --benchmark_filter="$benchmark_filter" --benchmark_format=json)
  if [ $dry = 1 ]; then
    run "${words[@]}"
    return
  fi
  local report
  report=$("${words[@]}" 2>/dev/null |
    python3 -c 'import json,sys; print(json.dumps(json.load(sys.stdin)))') || report=null
  echo "{\"suite\": \"$suite\", \"case\": $(json_string "$name"), \"side\": $(json_string "$(side_label "$side")"), \"round\": $round, \"threads\": ${count/-/null}, \"report\": $report}" >> "$file"
}

# A text suite's output in OUT/SUITE.txt (and on stdout).
text_suite() {
  local function=$1
  if [ $dry = 1 ]; then
    "$function"
    return
  fi
  "$function" > >(tee "$out/$suite.txt") 2>&1
  wait $!
}

checks() {  # finflex check of the bundled fish and rigs on the device, with `count` threads
  local side=$1 count=$2 mesh rig finflex
  finflex=$(program "$side" finflex)
  # shellcheck disable=SC2046
  for mesh in data/blub/fish.obj data/barramundi/BarramundiFish.gltf; do
    echo "== finflex check --in $mesh ${device_option[*]}"
    run env $(side_env "$side" "$count") "$finflex" check --in "$mesh" "${device_option[@]}" ||
      failed+=("check $mesh")
  done
  for rig in data/rigs/blub.rig.json data/rigs/blub_swim.rig.json; do
    echo "== finflex check --in data/blub/fish.obj --rig $rig ${device_option[*]}"
    # shellcheck disable=SC2046
    run env $(side_env "$side" "$count") "$finflex" check --in data/blub/fish.obj --rig "$rig" \
      "${device_option[@]}" || failed+=("check --rig $rig")
  done
}

# What only a GPU runs by default, and where it is tested:
#  - half normals stored with vstore_half (FF_GPU=1): every half-normal test of
#    test_normal_format, and test_rig_deformer's HeterogeneousFrameEqualsSeparateRuns;
#  - 2 (float32) or 4 (half normals, rigs) instances per work-item: every test of
#    test_cl_deformer, test_rig_deformer, test_normal_format and test_geometry;
#  - RigDispatch::kPerComponent: every rig test;
#  - the hardware's sine and cosine in the spine (FF_NATIVE_TRIG, NVIDIA's GPUs):
#    test_spine and test_swim against the double-precision reference, and
#    `finflex check` of the swim rig.
# CPUs run these too where they can be forced: the work-item shapes and the dispatch
# through ClOptions (SeveralInstancesPerWorkItemGiveTheSameResult in test_cl_deformer
# and test_rig_deformer, the rig tests of both dispatches, HalfNormalsInTheShapesGpusTake),
# vstore_half in a kernel of the test's own (EveryHalfStoreWritesTheNearestHalf).
gpu_checks() {
  local side test
  for side in "${sides[@]}"; do
    for test in "${device_tests[@]}"; do
      echo "== $test on the default device $(side_label "$side")"
      # --gtest_brief: every failure in full, then the summary.
      # shellcheck disable=SC2046
      run env $(side_env "$side" -) "$(program "$side" "$test")" --gtest_brief=1 ||
        failed+=("$test")
    done
    checks "$side" -
  done
  if [ ${#failed[@]} = 0 ]; then echo "== all passed"; else echo "== FAILED: ${failed[*]}"; fi
}

cpu_checks() {
  local side count
  for side in "${sides[@]}"; do
    for count in $threads; do checks "$side" "$count"; done
  done
}

bench_deform() {
  local round count side
  local -a extra=(--benchmark_counters_tabular=true)
  [ -n "$filter" ] && extra+=(--benchmark_filter="$filter")
  for round in $(seq "$rounds"); do
    for count in $threads; do
      for side in "${sides[@]}"; do
        echo "== bench_deform, round $round$([ "$count" = - ] || echo ", $count threads")" \
          "$(side_label "$side")"
        # shellcheck disable=SC2046
        run env $(side_env "$side" "$count") "$(program "$side" bench_deform)" "${extra[@]}"
      done
    done
  done
}

# The bundled fish with their swim rigs, for the suites that run `finflex swim`.
swim_species=(--species data/blub/fish.obj:data/rigs/blub_swim.rig.json
  --species data/barramundi/BarramundiFish.gltf:data/rigs/barramundi_swim.rig.json)

# One `finflex swim` of the suites that draw: WHAT, a time limit in seconds, then the
# options; its summary lines (not the files written). Uses the caller's $side and
# $finflex.
device_swim() {
  local what=$1 limit=$2
  shift 2
  echo "== $what"
  # shellcheck disable=SC2046
  run env $(side_env "$side" -) timeout "$limit" "$finflex" swim "${swim_species[@]}" \
    "${device_option[@]}" "$@" | grep -vE "^ *wrote|put back" || failed+=("$what")
}

# The rendering part of each summary.json under FOLDER (only KEYS, comma-separated,
# when given).
print_summaries() {
  local summary
  for summary in "$1"/*/summary.json; do
    [ -e "$summary" ] || continue
    python3 - "$summary" "${2:-}" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))["rendering"]
keys = sys.argv[2].split(",") if sys.argv[2] else list(s)
print("==", sys.argv[1].split("/")[-2], json.dumps({k: s[k] for k in s if k in keys}, indent=1))
PY
  done
}

render_speed() {
  find_nvidia_egl
  find_nvidia_vulkan
  local side finflex scratch path
  scratch=$(mktemp -d)
  # One swim of FISH fish on a path: its summary lines, and with --out its
  # summary.json's rendering part.
  swim_on() {
    local what=$1 path=$2 fish=$3
    shift 3
    device_swim "$what, --hand-off $path" 90 --fish "$fish" --size 1280x720 --hand-off "$path" "$@"
  }
  for side in "${sides[@]}"; do
    finflex=$(program "$side" finflex)
    [ ${#sides[@]} = 1 ] || echo "== side $(side_label "$side")"
    for path in external-memory copy; do
      swim_on "1,000 fish drawn only: 60 frames" "$path" 1000 --seconds 2 --fps 30 --render
    done
    for path in external-memory copy; do
      swim_on "1,000 fish, every frame a PNG: 30 frames" "$path" 1000 --seconds 1 --fps 30 \
        --out "$scratch/tank-$path" --video none
    done
    for path in external-memory copy; do
      swim_on "1,000 fish, a dataset (--annotate): 15 frames" "$path" 1000 --seconds 0.5 \
        --fps 30 --out "$scratch/dataset-$path" --video none --annotate
    done
    for path in external-memory copy; do
      swim_on "1,000 fish drawn and the reference draw: 30 frames" "$path" 1000 --seconds 1 \
        --fps 30 --render --reference-draw
    done
    swim_on "10,000 fish drawn only: 15 frames" external-memory 10000 --seconds 0.5 --fps 30 \
      --render
    print_summaries "$scratch"
    rm -rf "${scratch:?}"/*
  done
  rm -rf "$scratch"
}

dataset() {
  find_nvidia_egl
  find_nvidia_vulkan
  local side finflex scratch
  scratch=$(mktemp -d)
  dataset_swim() {
    local what=$1 name=$2
    shift 2
    device_swim "$what" 120 --fish 1000 --size 1280x720 --seconds 0.5 --fps 30 --annotate \
      --video none --out "$scratch/$name" "$@"
  }
  for side in "${sides[@]}"; do
    finflex=$(program "$side" finflex)
    [ ${#sides[@]} = 1 ] || echo "== side $(side_label "$side")"
    dataset_swim "mono, COCO: 15 frames" mono
    dataset_swim "mono, COCO, YOLO, depth: 15 frames" mono-all --formats coco,yolo --depth
    dataset_swim "stereo 0.12 m, COCO, YOLO, depth: 15 frames" stereo --formats coco,yolo \
      --depth --stereo 0.12
    dataset_swim "stereo 0.12 m, COCO, YOLO, depth, lens and noise: 15 frames" stereo-lens \
      --formats coco,yolo --depth --stereo 0.12 --distortion -0.2,0.05,0.001,-0.0005,0 \
      --noise 2,4
    dataset_swim "mono, COCO, YOLO, depth, refraction, water and light varied: 15 frames" \
      mono-optics --formats coco,yolo --depth --refraction --vary-optics
    dataset_swim "underwater camera, COCO, YOLO, depth: 15 frames" underwater \
      --formats coco,yolo --depth --camera underwater
    dataset_swim "underwater camera behind its flat port, COCO, YOLO, depth: 15 frames" \
      underwater-port --formats coco,yolo --depth --camera underwater --refraction
    print_summaries "$scratch" frames_per_second,seconds_per_frame_mean,share_of_frame,gpu
    rm -rf "${scratch:?}"/*
  done
  rm -rf "$scratch"
}

dataset_scaling() {
  find_nvidia_egl
  find_nvidia_vulkan
  local py scratch
  py=$(mktemp -d)
  scratch=$(mktemp -d)
  # The generator drives the finflex program and needs none of the Python module (which
  # a bundle does not hold): the package's dataset folder alone.
  mkdir -p "$py/finflex"
  cp -r bindings/python/finflex/dataset "$py/finflex/"
  : > "$py/finflex/__init__.py"
  # shellcheck disable=SC2046
  run env $(side_env A -) PYTHONPATH="$py${RAY_SITE:+:$RAY_SITE}" FINFLEX_DATA_DIR="$PWD/data" \
    python3 bench/dataset_scaling.py --finflex "$(program A finflex)" --out "$scratch" \
    || failed+=("dataset_scaling")
  rm -rf "$py" "$scratch"
}

level_choice() {
  local side mesh
  for side in "${sides[@]}"; do
    for mesh in blub/fish.obj:blub_swim barramundi/BarramundiFish.gltf:barramundi_swim; do
      echo "== finflex check --levels 4: ${mesh%%:*} $(side_label "$side")"
      # shellcheck disable=SC2046
      run env $(side_env "$side" -) "$(program "$side" finflex)" check --in "data/${mesh%%:*}" \
        --rig "data/rigs/${mesh##*:}.rig.json" --levels 4 "${device_option[@]}" ||
        failed+=("check --levels ${mesh%%:*}")
    done
    echo "== the level choice $(side_label "$side")"
    # shellcheck disable=SC2046
    run env $(side_env "$side" -) FINFLEX_RIG=data/rigs/blub_swim.rig.json \
      "$(program "$side" bench_deform)" --benchmark_filter=LevelChoice \
      --benchmark_counters_tabular=true || failed+=("level choice")
  done
}

render_levels() {
  find_nvidia_egl
  find_nvidia_vulkan
  local side finflex scratch
  scratch=$(mktemp -d)
  levels_swim() {
    local what=$1 fish=$2
    shift 2
    device_swim "$what" 120 --fish "$fish" --size 1920x1080 "$@"
  }
  for side in "${sides[@]}"; do
    finflex=$(program "$side" finflex)
    [ ${#sides[@]} = 1 ] || echo "== side $(side_label "$side")"
    levels_swim "1,000 fish drawn only, full detail: 60 frames" 1000 --seconds 2 --fps 30 --render
    levels_swim "1,000 fish drawn only, --levels 4: 60 frames" 1000 --seconds 2 --fps 30 --render \
      --levels 4
    levels_swim "1,000 fish, every frame a PNG, --levels 4: 30 frames" 1000 --seconds 1 --fps 30 \
      --out "$scratch/levels-png" --video none --levels 4
    levels_swim "10,000 fish drawn only, full detail: 15 frames" 10000 --seconds 0.5 --fps 30 --render
    levels_swim "10,000 fish drawn only, --levels 4: 15 frames" 10000 --seconds 0.5 --fps 30 \
      --render --levels 4
    levels_swim "10,000 fish drawn only, --levels 8: 15 frames" 10000 --seconds 0.5 --fps 30 \
      --render --levels 8
    levels_swim "the farm, 100,000 fish in 16 tanks drawn only, --levels 6: 30 frames" \
      100000 --tanks 16 --seconds 1 --fps 30 --levels 6 --render
    levels_swim "the farm, 100,000 fish in 16 tanks drawn, --levels 8: 60 frames (the last a PNG)" \
      100000 --tanks 16 --seconds 2 --fps 30 --levels 8 --out "$scratch/farm" --video none \
      --image-frames last
    cp "$scratch/farm/frames/frame_000059.png" "$out/render_levels_farm.png" ||
      failed+=("the farm's frame")
    levels_swim "the farm, 100,000 fish in 16 tanks drawn only, --levels 8 --no-wall-occlusion: 60 frames" \
      100000 --tanks 16 --seconds 2 --fps 30 --levels 8 --no-wall-occlusion --render
    levels_swim "the farm, 100,000 fish in 16 tanks drawn only, --levels 8 --pixel-budget 2: 60 frames" \
      100000 --tanks 16 --seconds 2 --fps 30 --levels 8 --pixel-budget 2 --render
    levels_swim "the farm, 100,000 fish in 16 tanks drawn only, full detail: 4 frames" 100000 \
      --tanks 16 --seconds 1 --fps 4 --render
  done
  rm -rf "$scratch"
}

handoff() {
  find_nvidia_egl
  find_nvidia_vulkan
  local side finflex scratch program
  scratch=$(mktemp -d)
  for side in "${sides[@]}"; do
    finflex=$(program "$side" finflex)
    echo "== finflex info $(side_label "$side")"
    # shellcheck disable=SC2046
    run env $(side_env "$side" -) "$finflex" info
    for program in test_gl_external test_pictures; do
      echo "== $program on the default device"
      # shellcheck disable=SC2046
      run env $(side_env "$side" -) FINFLEX_EXPECT_EXTERNAL_MEMORY=1 \
        timeout 120 "$(program "$side" "$program")" --gtest_brief=1 ||
        failed+=("$program")
    done
    echo "== vulkan_consumer on ${cl_device:-the default device}"
    # shellcheck disable=SC2046
    run env $(side_env "$side" -) timeout 60 "$(program "$side" vulkan_consumer)" data/blub/fish.obj \
      ${cl_device:+"$cl_device"} || failed+=("vulkan_consumer")
    echo "== the swim's frames on each path: 300 fish, 640x360, 12 frames"
    for path in external-memory copy; do
      # shellcheck disable=SC2046
      run env $(side_env "$side" -) timeout 60 "$finflex" swim --fish 300 --seconds 1 --fps 12 \
        --out "$scratch/$path" --video none --hand-off "$path" "${device_option[@]}" |
        grep -E "hand-off|rendered|a frame" || failed+=("swim --hand-off $path")
    done
    if [ $dry = 0 ]; then
      local differ=0
      for frame in "$scratch/external-memory/frames/"*.png; do
        cmp -s "$frame" "$scratch/copy/frames/$(basename "$frame")" || differ=$((differ + 1))
      done
      echo "== frames differing between the paths: $differ of" \
        "$(find "$scratch/copy/frames" -name '*.png' | wc -l)"
      [ "$differ" = 0 ] || failed+=("frames differ")
    fi
  done
  rm -rf "$scratch"
  if [ ${#failed[@]} = 0 ]; then echo "== all passed"; else echo "== FAILED: ${failed[*]}"; fi
}

# What the vectoriser says of each kernel: PoCL prints it when it compiles a kernel, on
# an empty cache.
remarks() {
  local finflex fish=data/blub/fish.obj rig=data/rigs/blub.rig.json
  local swim=data/rigs/blub_swim.rig.json raw
  finflex=$(program A finflex)
  raw=$(mktemp)
  local cache
  cache=$(mktemp -d)
  remark() {
    local name=$1
    shift
    echo "== $name"
    # shellcheck disable=SC2046
    run env $(side_env A -) POCL_CACHE_DIR="$cache" POCL_VECTORIZER_REMARKS=1 "$finflex" \
      bench --mesh "$fish" --instances 64 --frames 1 "${device_option[@]}" --json "$@"
  }
  {
    remark "bend paper, 1 lane" --lanes 1
    remark "bend paper, device lanes" --lanes 0
    remark "rig fused, 1 lane" --rig "$rig" --lanes 1
    remark "rig fused, device lanes" --rig "$rig" --lanes 0
    remark "rig passes, device lanes" --rig "$rig" --path passes --lanes 0
    remark "swim rig (spine) fused, 1 lane" --rig "$swim" --lanes 1
    remark "swim rig (spine) fused, device lanes" --rig "$swim" --lanes 0
  } > "$raw" 2>&1
  if [ $dry = 0 ] && [ -e docs/tools/vectorizer_remarks.py ]; then
    python3 docs/tools/vectorizer_remarks.py "$raw"
  else
    cat "$raw"
  fi
  rm -f "$raw"
}

info() {
  date -u
  echo "suites: ${suites[*]}; rounds: $rounds; threads: $threads; sides: ${sides[*]}"
  for side in "${sides[@]}"; do echo "side $side: $(side_label "$side") $(side_build "$side")"; done
  nproc
  lscpu | grep -E 'Model name|^CPU\(s\)|Thread|Core|Socket|NUMA node|L1d|L2|L3' | cut -c1-200
  grep MemTotal /proc/meminfo
  nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv 2>/dev/null
  (dpkg -l 2>/dev/null | grep -i pocl) || true
  # shellcheck disable=SC2046
  env $(side_env A -) "$(program A finflex)" info
}
[ $dry = 1 ] || info > "$out/info.txt" 2>&1

rig=data/rigs/blub.rig.json
swim=data/rigs/blub_swim.rig.json
for suite in "${suites[@]}"; do
  case $suite in
    finflex_bench)
      suite_frames=${frames:-30}
      cases=("bend paper|--mode paper"
        "bend paper, half normals|--mode paper --normal-format half"
        "bend exact|--mode exact"
        "rig fused|--rig $rig --path fused"
        "rig passes|--rig $rig --path passes"
        "swim rig (spine), no driver|--rig $swim"
        "swim|--rig $swim --swim")
      if [ $cpu = 1 ]; then
        suite_instances=${instances:-1000}
        cases+=("bend paper, plain stores|--stores plain"
          "bend paper, 8 lanes|--lanes 8"
          "bend paper, 1 lane|--lanes 1"
          "rig fused, 1 lane|--rig $rig --lanes 1"
          "swim rig (spine), no driver, 1 lane|--rig $swim --lanes 1")
      else
        suite_instances=${instances:-4000}
      fi
      bench_suite "${cases[@]}"
      ;;
    farm)
      suite_frames=${frames:-20}
      if [ $cpu = 1 ]; then suite_instances=${instances:-2000}; else suite_instances=${instances:-100000}; fi
      bench_suite "farm, 1 pixel|--rig $swim --farm" \
        "farm, 1 pixel, no wall occlusion|--rig $swim --farm --no-wall-occlusion" \
        "farm, 2 pixels|--rig $swim --farm --pixel-budget 2" \
        "farm, half normals|--rig $swim --farm --normal-format half" \
        "farm, 4 levels of a quarter of the triangles|--rig $swim --farm --levels 4 --triangle-ratio 0.25"
      ;;
    swim_bench)
      suite_frames=${frames:-50}
      suite_instances=${instances:-10000}
      bench_suite "swim, float32 normals|--rig $swim --swim" \
        "swim, the tank stepping in the frame loop|--rig $swim --swim --swim-inputs live" \
        "swim, half normals|--rig $swim --swim --normal-format half" \
        "swim, Jacobian normals|--rig $swim --swim --normals jacobian" \
        "swim, 2 instances per work-item|--rig $swim --swim --per-item 2" \
        "swim, 4 instances per work-item|--rig $swim --swim --per-item 4" \
        "swim rig, no driver, not placed|--rig $swim" \
        "whole-body bend|--mode paper"
      ;;
    layouts)
      suite_frames=${frames:-30}
      if [ $cpu = 1 ]; then suite_instances=${instances:-1000}; else suite_instances=${instances:-4000}; fi
      cases=()
      for deformation in "bend|" "rig|--rig $rig"; do
        for layout in planes interleaved compact snorm arrays; do
          for order in slots mesh; do
            cases+=("${deformation%%|*} $layout $order|${deformation#*|} --layout $layout --order $order")
          done
        done
        cases+=("${deformation%%|*} planes, previous positions|${deformation#*|} --previous"
          "${deformation%%|*} interleaved, half normals|${deformation#*|} --layout interleaved --normal-format half")
      done
      bench_suite "${cases[@]}"
      ;;
    sweep)
      suite_frames=${frames:-10}
      suite_instances=${instances:-"1 10 100 1000 4000"}
      scratch=$(mktemp -d)
      run "$(program A finflex)" subdivide --in data/blub/fish_control_mesh.obj --levels 5 \
        --out "$scratch/fish_112k.obj" > /dev/null
      cases=()
      for pair in data/blub/fish_low_resolution.obj:data/rigs/blub_low_resolution.rig.json \
        data/barramundi/BarramundiFish.gltf:data/rigs/barramundi.rig.json \
        data/blub/fish.obj:$rig "$scratch/fish_112k.obj:"; do
        mesh=${pair%%:*}
        mesh_rig=${pair#*:}
        name=$(basename "$mesh")
        cases+=("$name bend paper|--mesh $mesh --mode paper"
          "$name bend exact|--mesh $mesh --mode exact"
          "$name bend paper, half normals|--mesh $mesh --mode paper --normal-format half")
        if [ -n "$mesh_rig" ]; then
          cases+=("$name rig fused|--mesh $mesh --rig $mesh_rig --path fused"
            "$name rig passes|--mesh $mesh --rig $mesh_rig --path passes"
            "$name rig fused, half normals|--mesh $mesh --rig $mesh_rig --path fused --normal-format half")
        fi
      done
      bench_suite "${cases[@]}"
      rm -rf "$scratch"
      ;;
    pocl)
      [ $cpu = 1 ] || { echo "run.sh: the pocl suite runs with --cpu" >&2; exit 2; }
      suite_frames=${frames:-30}
      suite_instances=${instances:-1000}
      bench_suite "bend paper|--mode paper" "rig fused|--rig $rig" \
        "swim rig (spine), no driver|--rig $swim" "swim|--rig $swim --swim"
      for round in $(seq "$rounds"); do
        for count in $threads; do
          for number in $suite_instances; do
            for side in "${sides[@]}"; do
              baselines_line "$out/$suite.jsonl" "$round" "$count" "$side" \
                "OpenMP baselines, $number instances" "^BM_OpenMP(Simd)?Baseline/$number/"
            done
          done
        done
      done
      ;;
    gpu_checks | cpu_checks | bench_deform | render_speed | render_levels | dataset | \
      dataset_scaling | handoff | level_choice | remarks)
      text_suite "$suite" ;;
    *) echo "run.sh: '$suite' is not a suite (see --help)" >&2; exit 2 ;;
  esac
  if [ $dry = 0 ] && [ -e "$out/$suite.jsonl" ]; then
    python3 "$here/bench_table.py" "$out/$suite.jsonl"
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "== FAILED: ${failed[*]}"
  exit 1
fi
[ $dry = 1 ] || echo "== wrote $out"
