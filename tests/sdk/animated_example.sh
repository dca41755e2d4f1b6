#!/usr/bin/env bash
# The library API as an outside program uses it (issue 11): install this
# build into a fresh prefix, build examples/animated against that install
# only, and run it headless for a few small frames on every usable backend,
# with no PRISM_PLUGIN_PATH (the installed core finds its plugins itself).
# Each run must write frames that all differ, prepare the scene once and
# update it every later frame, and report its frame rate.
#   animated_example.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build="$1"
source="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
unset PRISM_PLUGIN_PATH
# Every Vulkan render of the tests runs under the Khronos validation layer; a
# message fails the render (here: the live updates' buffer uploads).
export PRISM_VULKAN_VALIDATION=1
frames=4

fail() { echo "FAIL: $*"; exit 1; }

cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
cmake -S "$source/examples/animated" -B "$work/example" -G Ninja \
  -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/configure.log"
cmake --build "$work/example" > "$work/build.log" || { cat "$work/build.log"; fail "the example does not build"; }
animated="$work/example/prism_animated"

# Bad arguments: exit status 2 and a message naming the flag.
expect_usage_error() {
  local expected="$1"; shift
  local status=0
  "$animated" "$@" > /dev/null 2> "$work/err.txt" || status=$?
  [ "$status" -eq 2 ] || fail "prism_animated $* exited $status, not 2"
  grep -q -- "$expected" "$work/err.txt" || { cat "$work/err.txt"; fail "prism_animated $*: no '$expected' in the message"; }
}
expect_usage_error "--frames: must be" --frames 0
expect_usage_error "--width: expected a whole number" --width wide
expect_usage_error "unknown argument '--bogus'" --bogus
expect_usage_error "--spp: needs a value" --spp
expect_usage_error "no-such-backend" --backend no-such-backend --frames 1

# Backends the installed `prism list` says are usable here.
"$work/prefix/bin/prism" list > "$work/list.txt"
mapfile -t usable < <(awk '/^backends:/ {on = 1; next} /^[a-z]/ {on = 0} on && / usable: / {print $1}' "$work/list.txt" | sort)
[ "${#usable[@]}" -gt 0 ] || fail "no usable backend"
# A backend CI requires must not be skipped silently.
IFS=, read -r -a required <<< "${PRISM_REQUIRE_BACKENDS:-}"
for name in "${required[@]}"; do
  [ -z "$name" ] || printf '%s\n' "${usable[@]}" | grep -qx "$name" || {
    cat "$work/list.txt"; fail "PRISM_REQUIRE_BACKENDS names $name, which cannot run here"; }
done

counter() { sed -n "s/^counters:.* $1 \([0-9]*\).*/\1/p" "$2"; }

for backend in "${usable[@]}"; do
  out="$work/frames_$backend"
  log="$work/run_$backend.txt"
  "$animated" --backend "$backend" --frames "$frames" --width 160 --height 90 --out "$out" > "$log" 2>&1 ||
    { cat "$log"; fail "$backend: prism_animated failed"; }
  for ((i = 0; i < frames; ++i)); do
    [ -s "$out/$(printf 'frame_%04d.png' "$i")" ] || { cat "$log"; fail "$backend: frame $i was not written"; }
  done
  distinct=$(md5sum "$out"/frame_*.png | awk '{print $1}' | sort -u | wc -l)
  [ "$distinct" -eq "$frames" ] || fail "$backend: only $distinct of $frames frames differ"
  grep -Eq '^median frame time: [0-9.]+ ms \([0-9.]+ FPS\)' "$log" || { cat "$log"; fail "$backend: no FPS reported"; }
  prepares=$(counter prepares "$log")
  updates=$(counter updates "$log")
  [ "$prepares" = 1 ] || { cat "$log"; fail "$backend: prepares is '$prepares', not 1"; }
  [ -n "$updates" ] && [ "$updates" -gt 0 ] || { cat "$log"; fail "$backend: updates is '$updates', not > 0"; }
  echo "$backend: $(grep '^median' "$log"); $(grep '^counters' "$log")"
done

# --window: the frames through Prism::view, under a private X server where
# there is one. The opengl backend (its own EGL context) beside the window's
# context is the case that matters, so it is preferred.
if ! command -v xvfb-run > /dev/null; then
  echo "--window not tested: xvfb-run is not installed (Debian package xvfb)"
  exit 0
fi
shown="${usable[0]}"
printf '%s\n' "${usable[@]}" | grep -qx opengl && shown=opengl
log="$work/window.txt"
xvfb-run -a -s "-screen 0 1280x1024x24 -nolisten tcp" \
  "$animated" --window --backend "$shown" --frames 3 --width 160 --height 90 > "$log" 2>&1 ||
  { cat "$log"; fail "--window with $shown failed"; }
grep -q '^median frame time: .* FPS' "$log" || { cat "$log"; fail "--window: no FPS reported"; }
echo "--window with $shown: $(grep '^median' "$log")"
