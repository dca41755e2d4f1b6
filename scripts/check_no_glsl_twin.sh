#!/usr/bin/env bash
# A primitive's intersector is written once (issue: one source per
# primitive for the CPU and the GPU): every plugin folder (plugins/<type>/,
# and the SDK's example, examples/primitive-plugin/; see plugin_folders.sh)
# holds its one source <type>.shared.glsl, which its C++ instantiates
# (`#define PRISM_SHARED_SOURCE "<type>.shared.glsl"`), and no other .glsl
# file, so a hand-written GLSL twin of the intersector cannot come back.
#
# `not_yet_shared` lists the plugins still waiting to be rewritten; each of
# them must still have its hand-written <type>.glsl (so the list shrinks as
# they move and cannot go stale), and an empty list is the goal.
#
#   scripts/check_no_glsl_twin.sh     exit status 1 naming every offence
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/scripts/plugin_folders.sh"
not_yet_shared=()

failures=0
fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}

pending() {
  local p
  for p in ${not_yet_shared[@]+"${not_yet_shared[@]}"}; do [[ "$p" == "$1" ]] && return 0; done
  return 1
}

checked=()
while read -r type dir; do
  checked+=("$type")
  where="${dir#"$root"/}"
  if pending "$type"; then
    [[ -f "$dir/$type.glsl" ]] || fail "$type is listed in not_yet_shared but has no $type.glsl: remove it from the list"
    continue
  fi
  [[ -f "$dir/$type.shared.glsl" ]] || fail "$where: no one source $type.shared.glsl"
  grep -q "^#define PRISM_SHARED_SOURCE \"$type.shared.glsl\"" "$dir/$type.cpp" ||
    fail "$where/$type.cpp does not instantiate $type.shared.glsl"
  for f in "$dir"/*.glsl; do
    [[ -e "$f" ]] || continue
    [[ "$(basename "$f")" == "$type.shared.glsl" ]] || fail "$where/$(basename "$f"): a hand-written GLSL twin"
  done
done < <(plugin_folders "$root")

if [[ $failures -gt 0 ]]; then
  echo "check_no_glsl_twin: $failures failure(s)" >&2
  exit 1
fi
echo "check_no_glsl_twin: every plugin is written once (${checked[*]}; not yet shared: ${not_yet_shared[*]:-none})"
