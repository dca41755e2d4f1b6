#!/usr/bin/env bash
# A primitive added as one folder is picked up by every suite (issue 24):
# with FOLDER (where that primitive's plugin and case module were built) on
# PRISM_PLUGIN_PATH, each suite must run TYPE and pass:
#   - `prism plugin fields --markdown` (the docs' field table) has its section
#   - prism_stability --quick --primitive TYPE (every usable backend)
#   - the trace-agreement tests of TYPE (every backend against the reference)
#   - its uv tests, when its cases have any
#   - the Embree backend's random scenes draw TYPE and match brute force
#   - the microbenchmarks list and run TYPE (when they are built)
#
#   ninth_primitive.sh FOLDER TYPE PRISM STABILITY AGREEMENT_TEST SHADING_TEST EMBREE_TEST [BENCH]
set -euo pipefail
if [ $# -ne 8 ] && [ $# -ne 7 ]; then
  echo "usage: $0 FOLDER TYPE PRISM STABILITY AGREEMENT_TEST SHADING_TEST EMBREE_TEST [BENCH]" >&2
  exit 2
fi
folder="$1" type="$2" prism="$3" stability="$4" agreement="$5" shading="$6" embree="$7" bench="${8:-}"
[ -f "$folder/libprism_primitive_$type.so" ] || { echo "ninth_primitive: no $type plugin in $folder"; exit 1; }
[ -f "$folder/libprism_cases_$type.so" ] || { echo "ninth_primitive: no $type case module in $folder"; exit 1; }
export PRISM_PLUGIN_PATH="$folder"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

echo "== the docs' field table"
"$prism" plugin fields --markdown > "$work/fields.md"
grep -q "^| \`$type\` | " "$work/fields.md" || { echo "ninth_primitive: no $type in the field table:"; cat "$work/fields.md"; exit 1; }
grep -A8 "$type" "$work/fields.md" | head -12

echo "== the stability suite"
"$stability" --quick --primitive "$type"

# gtest: the tests matching FILTER run (at least one) and none fails.
run_gtest() {
  local program="$1" filter="$2"
  "$program" --gtest_filter="$filter" | tee "$work/gtest.txt"
  grep -Eq '^\[  PASSED  \] [1-9][0-9]* test' "$work/gtest.txt" || {
    echo "ninth_primitive: no test of $type ran for $filter"; exit 1; }
}
echo "== trace agreement"
run_gtest "$agreement" "*TraceAgreement*_${type}*"
echo "== uv"
run_gtest "$shading" "*PrimitiveUvTest.*$(printf '%s' "${type:0:1}" | tr a-z A-Z)${type:1}*"

echo "== the Embree backend's random scenes"
run_gtest "$embree" "EmbreeQuery.RandomScenesHoldEveryAvailableType:EmbreeQuery.MatchesBruteForceOnRandomMixedScenes"
grep -Eq "types:.* $type( |\$)" "$work/gtest.txt" || { echo "ninth_primitive: the random scenes do not draw $type"; exit 1; }

if [ -n "$bench" ]; then
  echo "== microbenchmarks"
  "$bench" --benchmark_filter="/$type" --benchmark_min_time=0.001 | tee "$work/bench.txt"
  for name in "intersect/$type/hit" "intersect/$type/miss" "intersect_batch/$type/hit" "surface/$type"; do
    grep -q "^$name " "$work/bench.txt" || { echo "ninth_primitive: no benchmark $name"; exit 1; }
  done
  if grep -q "ERROR OCCURRED" "$work/bench.txt"; then
    echo "ninth_primitive: a benchmark of $type failed its setup"; exit 1
  fi
else
  echo "== microbenchmarks: not built here (Google Benchmark not found)"
fi
echo "ninth_primitive: $type passed every suite"
