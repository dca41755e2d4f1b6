#!/usr/bin/env bash
# Fuzzes the scene loader and the ray CSV reader of `prism trace` with
# libFuzzer under AddressSanitizer, UndefinedBehaviorSanitizer and
# LeakSanitizer: configures and builds build-fuzz/ (clang, -DPRISM_FUZZ=ON),
# writes the seed corpus, then runs each target for N seconds.
#
#   scripts/fuzz.sh [--seconds N] [--target scene_loader|ray_csv]
#
# Each target starts from its seeds (scenes/**/*.json and the bad inputs of
# the command-line tests, tests/fuzz/write_seeds.cpp), the corpus it grew in
# earlier runs (build-fuzz/fuzz/corpus/<target>, kept) and the inputs that
# once found a bug (tests/fuzz/regressions/<target>, replayed first).
# Exits non-zero on any finding: a crash, a sanitizer report, a leak, a
# hang (-timeout=30 s), memory over -rss_limit_mb, or an escaped exception. The
# input is kept in build-fuzz/fuzz/findings/<target>/<date-time>/ and the
# script prints how to reproduce it.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=60
targets=(scene_loader ray_csv)
while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) seconds="$2"; shift 2 ;;
    --target) targets=("$2"); shift 2 ;;
    *) echo "usage: scripts/fuzz.sh [--seconds N] [--target scene_loader|ray_csv]" >&2; exit 2 ;;
  esac
done
for t in "${targets[@]}"; do
  [ -f "tests/fuzz/fuzz_$t.cpp" ] || { echo "unknown target '$t' (scene_loader, ray_csv)" >&2; exit 2; }
done

CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPRISM_FUZZ=ON -DPRISM_SANITIZE=ON >/dev/null
cmake --build build-fuzz -j"$(nproc)"

work=build-fuzz/fuzz
rm -rf "$work/seeds"
build-fuzz/bin/prism_fuzz_seeds "$work/seeds/scene_loader" "$work/seeds/ray_csv"
# Every scene in the tree, flattened to one folder: scenes/conformance/box.json -> scenes_conformance_box.json.
find scenes -name '*.json' | while read -r f; do cp "$f" "$work/seeds/scene_loader/$(echo "${f%.json}" | tr / _).json"; done

# halt_on_error: UBSan's first report ends the run like ASan's does.
export ASAN_OPTIONS=abort_on_error=1:detect_leaks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
failed=0
for t in "${targets[@]}"; do
  corpus="$work/corpus/$t" findings="$work/findings/$t/$(date +%Y%m%d-%H%M%S)" log="$work/$t.log"
  mkdir -p "$corpus" "$findings"
  inputs=("$corpus" "$work/seeds/$t")
  [ -d "tests/fuzz/regressions/$t" ] && inputs+=("tests/fuzz/regressions/$t")
  echo "fuzz_$t: ${seconds} s (log: $log)"
  # -timeout is wall-clock: 30 s, not less, because a scene with ten textures
  # takes ~5 s through OpenImageIO under ASan on a busy 2-core machine
  # (a 10 s limit reported that as a hang); a real hang never ends.
  if build-fuzz/bin/"fuzz_$t" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=2048 -detect_leaks=1 \
       -dict="tests/fuzz/$t.dict" -artifact_prefix="$findings/" -print_final_stats=1 "${inputs[@]}" >"$log" 2>&1; then
    grep -E '^(Done|stat::number_of_executed_units)' "$log" || true
    rmdir "$findings"  # empty: nothing found
  else
    failed=1
    tail -n 60 "$log"
    echo "fuzz_$t FOUND A BUG. Inputs kept:" >&2
    ls -1 "$findings"/* >&2 2>/dev/null || true
    echo "Reproduce: build-fuzz/bin/fuzz_$t <input file>   (full log: $log)" >&2
  fi
done
exit "$failed"
