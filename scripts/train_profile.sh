#!/usr/bin/env bash
# usage: scripts/train_profile.sh [BUILD_DIR]
#
# The training renders of profile-guided optimisation (PRISM_PGO in
# CMakeLists.txt). Run on a build configured with -DPRISM_PGO=generate after
# building its target prism_profile_training; the instrumented libraries
# write their counts under the build's PRISM_PGO_DIR as each render exits.
# scripts/setup.sh runs it between the instrumented build and the final one
# (-DPRISM_PGO=use).
#
# What a frame runs is what the profile should weigh: the bench's two
# scenes at its settings (640x360, 1 spp, depth 5), the showcase written to
# PNG (its rays take the light buffers and the box filter) and 100,000
# random spheres (Embree's BVH), then every conformance scene once, so that
# each primitive, light and material path has counts. Trained on the
# showcase alone, the spheres' frames came out ~10 % slower than without a
# profile. About 3 s on a 2-core machine.
#
# Exit status: 0 when every render succeeded, 1 otherwise, 2 on bad usage.
set -euo pipefail

usage() { sed -n '/^# usage:/,/^# Exit status/p' "$0" | sed 's/^# \{0,1\}//'; }
case "${1:-}" in
  -h | --help) usage; exit 0 ;;
esac
[ $# -le 1 ] || { usage >&2; exit 2; }
cd "$(dirname "$0")/.."
build="${1:-build}"

pgo_setting() { sed -n "s/^$1:[A-Z]*=//p" "$build/CMakeCache.txt"; }
[ -f "$build/CMakeCache.txt" ] || { echo "train_profile.sh: no configured build at $build" >&2; exit 2; }
if [ "$(pgo_setting PRISM_PGO)" != "generate" ]; then
  echo "train_profile.sh: $build is not configured with -DPRISM_PGO=generate" >&2
  exit 2
fi
profiles="$(pgo_setting PRISM_PGO_DIR)"
[ -n "$profiles" ] || { echo "train_profile.sh: $build names no PRISM_PGO_DIR" >&2; exit 2; }
prism="$build/bin/prism"

# Counts add up over runs: a fresh start, so that no older build's counts remain.
rm -rf "$profiles"
out="$(mktemp -d "${TMPDIR:-/tmp}/prism-training.XXXXXX")"
trap 'rm -rf "$out"' EXIT

bench=(-b embree --width 640 --height 360 --spp 1 --max-depth 5 -q)
"$prism" render scenes/showcase.json "${bench[@]}" -o "$out/showcase.png"
"$build/bin/prism_make_spheres" -o "$out/spheres.json"
"$prism" render "$out/spheres.json" "${bench[@]}" -o "$out/spheres.exr"
for scene in scenes/conformance/*.json; do
  "$prism" render "$scene" -b embree -q -o "$out/conformance.exr"
done
echo "trained: $(find "$profiles" -name '*.gcda' | wc -l) profiles in $profiles"
