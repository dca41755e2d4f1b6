#!/usr/bin/env bash
# Renders the stored high-spp reference images of the conformance suite:
# every scenes/conformance/<name>.json with the reference backend (CPU, double
# precision) at 256 samples per pixel, to tests/conformance/references/<name>.exr
# (linear RGB stored as half float, the scene's own width, height and max_depth:
# half's relative rounding of 5e-4 is far below the 16-spp noise the sweep
# measures, and it halves the files).
#
# These files change ONLY by running this script. They are the truth that
# `prism conform --sweep` measures its error-vs-spp and error-vs-time curves
# against (every backend at spp 1, 2, 4, ... --sweep-max-spp, default 16): an
# image edited by hand, rendered at another spp or by another backend would
# move every curve without any backend having changed. Rerun the script, and
# commit its output, whenever a conformance scene is added or edited, or when
# the reference backend's picture legitimately changes.
#
# spp: 256 for every scene. Measured on a 2-core machine: 0.6-2 s per scene,
# the slowest depth.json (3-5 s) and showcase.json (3-4 s); about 40 s for all
# 31 scenes. No scene comes near 30 s, so none needed fewer samples. The sweep
# stops at 16 spp by default, so the stored image has at least 16 times the
# samples of any point it is compared with.
#
# Usage: scripts/make_conformance_references.sh [scene.json ...]
#   (no arguments: every scenes/conformance/*.json)
# Environment: PRISM = the prism binary (default build/bin/prism),
#              SPP = samples per pixel (default 256; keep it at 256 for committed files).
set -euo pipefail
cd "$(dirname "$0")/.."

prism="${PRISM:-build/bin/prism}"
spp="${SPP:-256}"
out_dir=tests/conformance/references

if [[ ! -x "$prism" ]]; then
  echo "error: no prism binary at $prism (build the project first, or set PRISM)" >&2
  exit 1
fi
mkdir -p "$out_dir"

if (($# > 0)); then
  scenes=("$@")
else
  shopt -s nullglob
  scenes=(scenes/conformance/*.json)
  shopt -u nullglob
fi
if ((${#scenes[@]} == 0)); then
  echo "error: no scenes in scenes/conformance/" >&2
  exit 1
fi

for scene in "${scenes[@]}"; do
  name="$(basename "$scene" .json)"
  final="$out_dir/$name.exr"
  # Written to a temporary name in the same folder, then renamed: an
  # interrupted run never leaves a half-written reference behind.
  tmp="$out_dir/.$name.tmp.$$.exr"
  rendered="$out_dir/.$name.float.$$.exr"
  trap 'rm -f "$tmp" "$rendered"' EXIT
  start=$(date +%s.%N)
  "$prism" render "$scene" -b reference --spp "$spp" -o "$rendered"
  oiiotool "$rendered" -d half --compression zip -o "$tmp"
  rm -f "$rendered"
  mv -f "$tmp" "$final"
  trap - EXIT
  end=$(date +%s.%N)
  printf '%-24s %4d spp  %6.1f s  %7d bytes\n' "$name" "$spp" "$(awk "BEGIN { print $end - $start }")" \
    "$(wc -c <"$final")"
done
