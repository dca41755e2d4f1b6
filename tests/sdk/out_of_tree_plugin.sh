#!/usr/bin/env bash
# The out-of-tree plugin path, end to end (issue 9): install this build into a
# fresh prefix, build examples/primitive-plugin against that install only,
# put it on PRISM_PLUGIN_PATH, render its scene through every usable backend,
# and compare every backend with the reference (`prism conform`).
#   out_of_tree_plugin.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build="$1"
source="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
cmake -S "$source/examples/primitive-plugin" -B "$work/example" -G Ninja \
  -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/configure.log"
cmake --build "$work/example"

prism="$work/prefix/bin/prism"
scene="$source/examples/primitive-plugin/capsule.json"
export PRISM_PLUGIN_PATH="$work/example/plugins"

"$prism" list > "$work/list.txt"
grep -q '^  capsule ' "$work/list.txt" || { echo "prism list does not show the capsule plugin:"; cat "$work/list.txt"; exit 1; }

# Backends `prism list` says are usable here, reference first.
mapfile -t usable < <(awk '/^backends:/ {on = 1; next} /^[a-z]/ {on = 0} on && / usable: / {print $1}' "$work/list.txt" | sort)
[ "${#usable[@]}" -gt 0 ] || { echo "no usable backend"; exit 1; }
# A backend CI requires must not be skipped silently.
IFS=, read -r -a required <<< "${PRISM_REQUIRE_BACKENDS:-}"
for name in "${required[@]}"; do
  [ -z "$name" ] || printf '%s\n' "${usable[@]}" | grep -qx "$name" || {
    echo "PRISM_REQUIRE_BACKENDS names $name, which cannot run here:"; cat "$work/list.txt"; exit 1; }
done
for backend in "${usable[@]}"; do
  "$prism" render "$scene" -b "$backend" -o "$work/capsule_$backend.png"
  echo "rendered with $backend"
done

others=()
for backend in "${usable[@]}"; do
  [ "$backend" = reference ] || others+=("$backend")
done
if [ "${#others[@]}" -gt 0 ]; then
  (IFS=,; "$prism" conform "$scene" -b "${others[*]}" --references "$work/no-references" --report "$work/report")
fi
