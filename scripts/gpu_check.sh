#!/usr/bin/env bash
# The checks to run on a machine with a real GPU (issue "real-time GPU
# kernels"): what the drivers are, the precision each showcase object gets,
# the showcase's frame time at 1920x1080 and 640x360 with the profile, the
# conformance suite and the quick stability suite, on both GPU backends.
# Prints everything; writes the conformance and stability reports to OUT.
#
# usage: scripts/gpu_check.sh [--build DIR] [--out DIR]
#   --build DIR  the build tree (default build/)
#   --out DIR    where the reports go (default out/gpu-check)
# Exit status: 0 when the conformance and stability suites pass, else 1.
set -uo pipefail
cd "$(dirname "$0")/.."

build=build
out=out/gpu-check
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    *) echo "gpu_check.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
prism="$build/bin/prism"
[ -x "$prism" ] || { echo "gpu_check.sh: no $prism (build first)" >&2; exit 2; }
mkdir -p "$out"
export PRISM_REQUIRE_BACKENDS="${PRISM_REQUIRE_BACKENDS:-reference,opengl,vulkan}"

step() { echo; echo "=== $*"; }
bench() { "$prism" bench scenes/showcase.json -b opengl,vulkan --spp 1 --max-depth 5 "$@"; }

step "backends"; "$prism" list
step "precision per object"; "$prism" list scenes/showcase.json
step "showcase 1920x1080"; bench --width 1920 --height 1080 --frames 100 --warmup 5
step "showcase 1920x1080, profiled"; bench --width 1920 --height 1080 --frames 30 --profile --no-check
step "showcase 640x360"; bench --frames 50 --warmup 3
status=0
step "conformance"; "$prism" conform -b opengl,vulkan --report "$out/conform" || status=1
step "stability (quick)"; "$build/bin/prism_stability" --quick -b opengl,vulkan --out "$out/stability" || status=1
exit $status
