#!/usr/bin/env bash
# Builds the Google Benchmark microbenchmarks in a Release tree (build-release/)
# and runs them, 5 repetitions each, aggregates only:
#   prism_bench_primitives  each primitive plugin's CPU intersector (hit/miss, single/batch, surface)
#   prism_bench_embree      Backend::trace through the embree backend (showcase, many spheres)
#                           and a 640x360 1 spp render of the showcase
#
# usage: scripts/microbench.sh [--json DIR] [ARGS...]
#   --json DIR   also write Google Benchmark JSON to DIR/primitives.json and DIR/embree.json
#   ARGS         passed to both programs (e.g. --benchmark_filter=torus, --benchmark_min_time=1),
#                except --showcase=FILE, --spheres=N and --spheres_file=FILE, which only
#                prism_bench_embree takes (default: 100,000 spheres generated in memory)
# Needs libbenchmark-dev. Later arguments override the defaults (e.g. --benchmark_repetitions=1).
set -euo pipefail
cd "$(dirname "$0")/.."

json_dir=""
common=()
embree_only=()
while [ $# -gt 0 ]; do
  case "$1" in
    --json)
      [ $# -ge 2 ] || { echo "microbench.sh: --json needs a folder" >&2; exit 2; }
      json_dir="$2"
      shift 2
      ;;
    --json=*) json_dir="${1#--json=}"; shift ;;
    --showcase=* | --spheres=* | --spheres_file=*) embree_only+=("$1"); shift ;;
    *) common+=("$1"); shift ;;
  esac
done

cmake -S . -B build-release -G Ninja -DCMAKE_BUILD_TYPE=Release
# The two programs depend on the plugins they load (bench/micro/CMakeLists.txt).
cmake --build build-release -j"$(nproc)" --target prism_bench_primitives prism_bench_embree

# Load this tree's Release plugins, whatever PRISM_PLUGIN_PATH says outside.
export PRISM_PLUGIN_PATH="$PWD/build-release/lib/prism"

run() {
  local name="$1" program="$2"
  shift 2
  local out=()
  if [ -n "$json_dir" ]; then
    mkdir -p "$json_dir"
    out=(--benchmark_out="$json_dir/$name.json" --benchmark_out_format=json)
  fi
  "build-release/bin/$program" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
    "${out[@]}" "$@"
}

run primitives prism_bench_primitives "${common[@]}"
run embree prism_bench_embree "${embree_only[@]}" "${common[@]}"
