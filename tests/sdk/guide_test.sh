#!/usr/bin/env bash
# The plugin guide (docs/writing-a-primitive-plugin.md) must not drift from
# the code (issue 9):
#  (a) every code block of the guide preceded by a line `<!-- file: NAME -->`
#      is (a consecutive part of) examples/primitive-plugin/NAME: the blocks
#      of one file, put together in order, must equal it byte for byte, and
#      every file of the example but README.md must be covered;
#  (b) the guide's shell steps (```sh blocks preceded by `<!-- run -->`) run,
#      in order, in one `set -euo pipefail` shell, in an empty folder holding
#      only the files put together from the guide, against a fresh install of
#      BUILD_DIR (`cmake --install BUILD_DIR --prefix P`, PRISM_PREFIX=P);
#  (c) every picture a step renders (`prism render ... -o FILE`) is a PNG.
#
#   guide_test.sh BUILD_DIR SOURCE_DIR [GUIDE]
#
# GUIDE defaults to SOURCE_DIR/docs/writing-a-primitive-plugin.md. Set
# PRISM_GUIDE_KEEP=1 to keep the work folder for a look afterwards.
set -euo pipefail

if [ $# -lt 2 ] || [ $# -gt 3 ]; then
  echo "usage: $0 BUILD_DIR SOURCE_DIR [GUIDE]" >&2
  exit 2
fi
build="$(cd "$1" && pwd)"
source="$(cd "$2" && pwd)"
guide="${3:-$source/docs/writing-a-primitive-plugin.md}"
example="$source/examples/primitive-plugin"
for need in "$guide" "$example/CMakeLists.txt"; do
  [ -f "$need" ] || { echo "guide_test: $need does not exist" >&2; exit 2; }
done

work="$(mktemp -d "${TMPDIR:-/tmp}/prism-guide.XXXXXX")"
if [ "${PRISM_GUIDE_KEEP:-0}" = 1 ]; then
  trap 'echo "guide_test: work folder kept: $work"' EXIT
else
  trap 'rm -rf "$work"' EXIT
fi
mkdir "$work/files"
: > "$work/files.txt"

# --- (a) Take the guide apart -------------------------------------------------
# files/NAME: the file blocks of NAME, in order; files.txt: the names, first
# use first; steps.sh: the run blocks, each announced by an echo.
awk -v files="$work/files" -v list="$work/files.txt" -v steps="$work/steps.sh" '
  function die(msg) {
    printf "guide_test: %s:%d: %s\n", FILENAME, FNR, msg > "/dev/stderr"
    failed = 1
    exit 1
  }
  BEGIN { print "set -euo pipefail" > steps }
  state == "open" {
    if ($0 !~ /^```/) die("a `<!-- file: NAME -->` or `<!-- run -->` line must be followed by a ``` line")
    if (kind == "run" && $0 != "```sh") die("a `<!-- run -->` block must be a ```sh block, got " $0)
    if (kind == "run") {
      runs++
      printf "echo \"guide_test: step %d (guide line %d)\"\n", runs, FNR + 1 > steps
    }
    state = "in"
    next
  }
  state == "in" {
    if ($0 ~ /^```[ \t]*$/) { state = ""; next }
    if (kind == "run") print > steps
    else print > (files "/" name)
    next
  }
  /^<!-- file: [^ ]+ -->$/ {
    name = $3
    if (name !~ /^[A-Za-z0-9_.-]+(\/[A-Za-z0-9_.-]+)*$/ || name ~ /(^|\/)\.\.?(\/|$)/)
      die("unusable file name " name)
    if (!(name in seen)) {
      seen[name] = 1
      print name > list
      if (name ~ /\//) {
        dir = name
        sub(/\/[^\/]*$/, "", dir)
        system("mkdir -p \"" files "/" dir "\"")
      }
    }
    kind = "file"
    state = "open"
    next
  }
  /^<!-- run -->$/ { kind = "run"; state = "open"; next }
  /^<!-- *(file|run)/ { die("malformed marker line: " $0) }
  END {
    if (failed) exit 1
    if (state != "") die("the last code block is not closed")
    if (runs == 0) die("no `<!-- run -->` block")
  }
' "$guide"

status=0
while IFS= read -r name; do
  if [ ! -f "$example/$name" ]; then
    echo "guide_test: the guide has blocks for $name, which examples/primitive-plugin does not have"
    status=1
  elif ! cmp -s "$example/$name" "$work/files/$name"; then
    echo "guide_test: the guide's blocks for $name, put together, differ from examples/primitive-plugin/$name"
    echo "  (--- the example, +++ the guide):"
    diff -u --label "examples/primitive-plugin/$name" --label "guide: $name" "$example/$name" "$work/files/$name" || true
    status=1
  fi
done < "$work/files.txt"
while IFS= read -r -d '' path; do
  name="${path#"$example"/}"
  [ "$name" = README.md ] && continue
  if ! grep -qxF -- "$name" "$work/files.txt"; then
    echo "guide_test: examples/primitive-plugin/$name is in no \`<!-- file: $name -->\` block of the guide"
    status=1
  fi
done < <(find "$example" -type f -print0 | sort -z)
if [ "$status" -ne 0 ]; then
  echo "guide_test: FAILED: $guide has drifted from examples/primitive-plugin"
  exit 1
fi
echo "guide_test: the guide's file blocks are the example's files ($(tr '\n' ' ' < "$work/files.txt"))"

# --- (b) Run the steps in an empty folder against a fresh install -------------
if ! cmake --install "$build" --prefix "$work/prefix" > "$work/install.log" 2>&1; then
  cat "$work/install.log"
  echo "guide_test: FAILED: cmake --install $build"
  exit 1
fi
mkdir "$work/plugin"
cp -R "$work/files/." "$work/plugin/"
echo "guide_test: running the guide's steps in $work/plugin"
if ! (cd "$work/plugin" &&
      unset PRISM_PLUGIN_PATH &&
      export PRISM_PREFIX="$work/prefix" &&
      bash "$work/steps.sh"); then
  echo "guide_test: FAILED: a step of the guide failed (above: the step and its output)"
  exit 1
fi

# --- (c) The pictures the steps rendered ---------------------------------------
mapfile -t pictures < <(awk '/prism"? render / { for (i = 1; i < NF; ++i) if ($i == "-o") { f = $(i + 1); gsub(/"/, "", f); print f } }' "$work/steps.sh")
if [ "${#pictures[@]}" -eq 0 ]; then
  echo "guide_test: FAILED: no step renders a picture (\`prism render ... -o FILE\`)"
  exit 1
fi
for picture in "${pictures[@]}"; do
  file="$work/plugin/$picture"
  [ -f "$file" ] || { echo "guide_test: FAILED: the guide renders $picture, which does not exist"; exit 1; }
  signature="$(head -c 16 "$file" | od -An -tx1 | tr -d ' \n')"
  # The PNG signature, then the first chunk's length and type: IHDR.
  if [ "${signature:0:16}" != 89504e470d0a1a0a ] || [ "${signature:24:8}" != 49484452 ]; then
    echo "guide_test: FAILED: $picture is not a PNG (starts with $signature)"
    exit 1
  fi
  echo "guide_test: $picture is a PNG ($(wc -c < "$file") bytes)"
done
echo "guide_test: passed"
