#!/usr/bin/env bash
# Peer comparison: renders the showcase with POV-Ray 3.7 (bench/povray/showcase.pov,
# the same scene written by hand) and with Prism, same resolution, 1 sample per
# pixel (no antialiasing in POV-Ray), same reflection depth (max_trace_level =
# --max-depth), and prints the time ratio and the throughput ratio.
#
# Runs: one untimed warm-up of each, then N runs, each one POV-Ray render and
# one Prism render back to back (the order alternates run by run), and the
# medians. Times compared (the ratio line uses these):
#   POV-Ray  "Trace Time" from its own statistics (the render phase: no parsing,
#            no bounding, no file output), plus its CPU-seconds from the same line
#   Prism    "ms"."render" from --stats (not load, build or image output)
# Wall-clock of each whole process is measured and printed too.
# Rays: POV-Ray's "Rays" (camera, reflected, refracted and transmitted rays)
# plus its "Shadow Ray Tests"; Prism's "rays" (all kinds, shadow rays included).
# docs/povray-comparison.md says what each count includes and what differs.
#
# usage: scripts/compare_povray.sh [--runs N] [-b BACKEND] [--width W --height H]
#                                  [--max-depth D] [--threads N] [--keep DIR]
#   --runs N       timed runs of each renderer (default 5)
#   -b BACKEND     Prism backend (default embree)
#   --width W, --height H   image size (default 640x360)
#   --max-depth D  Prism --max-depth = POV-Ray max_trace_level (default 5)
#   --threads N    threads for both (default: all, nproc): POV-Ray +WTN; below
#                  nproc both run pinned to CPUs 0..N-1 with taskset (Prism's TBB
#                  pool follows the affinity mask); --threads 1 = single-thread
#   --keep DIR     keep the images there: prism.png, povray.png,
#                  side_by_side.png (Prism left, POV-Ray right), diff_x4.png
#                  (|Prism - POV-Ray| x 4), the POV-Ray log and Prism's stats
# Environment: PRISM = the prism binary (default build/bin/prism).
# Exit status: 0 done, 1 a renderer is missing or failed, 2 bad arguments.
set -euo pipefail

usage() { sed -n '/^# usage:/,/^# Exit status/p' "$0" | sed 's/^# \{0,1\}//'; }
die_usage() { echo "compare_povray.sh: $1" >&2; usage >&2; exit 2; }

runs=5
backend=embree
width=640
height=360
depth=5
threads="$(nproc)"
keep=""
while [ $# -gt 0 ]; do
  case "$1" in
    -h | --help) usage; exit 0 ;;
    --runs | -b | --backend | --width | --height | --max-depth | --threads | --keep)
      [ $# -ge 2 ] || die_usage "$1 needs a value"
      case "$1" in
        --runs) runs="$2" ;;
        -b | --backend) backend="$2" ;;
        --width) width="$2" ;;
        --height) height="$2" ;;
        --max-depth) depth="$2" ;;
        --threads) threads="$2" ;;
        --keep) keep="$2" ;;
      esac
      shift 2
      ;;
    --runs=* | --backend=* | --width=* | --height=* | --max-depth=* | --threads=* | --keep=*)
      value="${1#*=}"
      case "$1" in
        --runs=*) runs="$value" ;;
        --backend=*) backend="$value" ;;
        --width=*) width="$value" ;;
        --height=*) height="$value" ;;
        --max-depth=*) depth="$value" ;;
        --threads=*) threads="$value" ;;
        --keep=*) keep="$value" ;;
      esac
      shift
      ;;
    *) die_usage "unknown argument '$1'" ;;
  esac
done

is_count() { [[ "$1" =~ ^[0-9]+$ ]] && [ "$((10#$1))" -ge "$2" ] && [ "$((10#$1))" -le "$3" ]; }
is_count "$runs" 1 1000 || die_usage "--runs must be an integer in 1..1000, got '$runs'"
is_count "$width" 1 16384 || die_usage "--width must be an integer in 1..16384, got '$width'"
is_count "$height" 1 16384 || die_usage "--height must be an integer in 1..16384, got '$height'"
is_count "$depth" 1 64 || die_usage "--max-depth must be an integer in 1..64, got '$depth'"
is_count "$threads" 1 512 || die_usage "--threads must be an integer in 1..512, got '$threads'"
[[ "$backend" =~ ^[A-Za-z0-9_.-]+$ ]] || die_usage "bad backend name '$backend'"
runs=$((10#$runs)) width=$((10#$width)) height=$((10#$height)) depth=$((10#$depth)) threads=$((10#$threads))

if [ -n "$keep" ]; then
  keep="$(realpath -m -- "$keep")"
fi
cd "$(dirname "$0")/.."

prism="${PRISM:-build/bin/prism}"
if [ ! -x "$prism" ]; then
  echo "error: no prism binary at $prism (build the project first, or set PRISM)" >&2
  exit 1
fi
prism="$(realpath -- "$prism")"
if ! command -v povray >/dev/null 2>&1; then
  echo "error: povray is not installed. Install POV-Ray 3.7 (Debian package povray):" >&2
  echo "  sudo apt-get install -y --no-install-recommends povray" >&2
  exit 1
fi
pin=()
if [ "$threads" -lt "$(nproc)" ]; then
  command -v taskset >/dev/null 2>&1 || { echo "error: --threads below nproc needs taskset (util-linux)" >&2; exit 1; }
  pin=(taskset -c "0-$((threads - 1))")
fi

# POV-Ray's default file-I/O security reads only from the current folder (and
# a few system ones), so the scene and its textures go into one work folder
# and POV-Ray runs there.
work="$(mktemp -d "${TMPDIR:-/tmp}/prism-povray.XXXXXX")"
trap 'rm -rf "$work"' EXIT
cp bench/povray/showcase.pov scenes/textures/*.png "$work/"
scene="$PWD/scenes/showcase.json"

# Runs a command, its stdout and stderr to $2, and sets `elapsed` to its
# wall-clock seconds. Fails the script, showing the log, if the command fails.
elapsed=0
timed() {
  local label="$1" log="$2"
  shift 2
  local TIMEFORMAT=%3R t rc=0
  t="$( { time "$@" >"$log" 2>&1; } 2>&1 )" || rc=$?
  if [ "$rc" -ne 0 ]; then
    echo "error: $label failed (exit status $rc); the end of its output:" >&2
    tail -n 20 "$log" | tr '\r' '\n' | tail -n 20 >&2
    exit 1
  fi
  elapsed="$t"
}

# $1 = run name. Sets pov_trace, pov_cpu, pov_wall, pov_rays, pov_shadow,
# pov_primary (Rays: camera+reflected+refracted+transmitted).
run_povray() {
  local name="$1" log="$work/povray_$1.log"
  timed "povray" "$log" \
    "${pin[@]}" env -C "$work" povray +Ishowcase.pov "+Opovray_$name.png" +FN "+W$width" "+H$height" \
    -A "+WT$threads" -D File_Gamma=sRGB "Declare=MaxDepth=$depth"
  pov_wall="$elapsed"
  # "  Trace Time:  0 hours  0 minutes  0 seconds (0.356 seconds)" and next line
  # "              using 2 thread(s) with 0.512 CPU-seconds total"
  pov_trace="$(tr '\r' '\n' <"$log" | sed -n 's/^ *Trace Time:.*(\([0-9.]*\) seconds).*/\1/p' | tail -n 1)"
  pov_cpu="$(tr '\r' '\n' <"$log" | sed -n '/Trace Time:/{n;s/.* with \([0-9.]*\) CPU-seconds.*/\1/p;}' | tail -n 1)"
  pov_primary="$(tr '\r' '\n' <"$log" | sed -n 's/^Rays: *\([0-9]*\).*/\1/p' | tail -n 1)"
  pov_shadow="$(tr '\r' '\n' <"$log" | sed -n 's/^Shadow Ray Tests: *\([0-9]*\).*/\1/p' | tail -n 1)"
  if [ -z "$pov_trace" ] || [ -z "$pov_primary" ]; then
    echo "error: could not read Trace Time / Rays from POV-Ray's statistics ($log)" >&2
    exit 1
  fi
  [ -n "$pov_cpu" ] || pov_cpu="?"
  [ -n "$pov_shadow" ] || pov_shadow=0 # no light source, no shadow tests line
  pov_rays=$((pov_primary + pov_shadow))
}

# $1 = run name. Sets prism_render (s), prism_wall, prism_rays.
run_prism() {
  local name="$1" stats="$work/prism_$1.json"
  timed "prism ($backend)" "$work/prism_$name.log" \
    "${pin[@]}" "$prism" render "$scene" -b "$backend" -o "$work/prism_$name.png" \
    --width "$width" --height "$height" --spp 1 --max-depth "$depth" --stats "$stats"
  prism_wall="$elapsed"
  local ms
  ms="$(sed -n 's/^ *"render": *\([0-9.eE+-]*\).*/\1/p' "$stats" | head -n 1)"
  prism_rays="$(sed -n 's/^ *"rays": *\([0-9]*\).*/\1/p' "$stats" | head -n 1)"
  if [ -z "$ms" ] || [ -z "$prism_rays" ]; then
    echo "error: could not read ms.render / rays from $stats" >&2
    exit 1
  fi
  prism_render="$(awk -v ms="$ms" 'BEGIN { printf "%.4f", ms / 1000 }')"
}

median() { printf '%s\n' "$@" | sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }

echo "POV-Ray: $(povray --version 2>&1 | sed -n 's/^POV-Ray \([0-9][^ ]*\).*/\1/p' | head -n 1)" \
  "(+WT$threads), Prism: $backend,$([ ${#pin[@]} -gt 0 ] && echo " both pinned to CPUs ${pin[2]},")" \
  "${width}x${height}, 1 spp, depth $depth, $runs runs"
echo "warm-up (untimed) ..."
run_povray warmup
run_prism warmup

printf '\n%-4s %-13s %9s %9s %9s %10s %9s %9s %10s %7s\n' run order pov_trace pov_cpu pov_wall pov_rays \
  prism_rnd prism_wall prism_rays time_x
printf '%-4s %-13s %9s %9s %9s %10s %9s %9s %10s %7s\n' "" "" "(s)" "(s)" "(s)" "" "(s)" "(s)" "" "pov/pr"
pt=() pc=() pw=() pr=() qt=() qw=() qr=()
for ((i = 1; i <= runs; i++)); do
  if ((i % 2)); then
    order="povray,prism"
    run_povray "$i"
    run_prism "$i"
  else
    order="prism,povray"
    run_prism "$i"
    run_povray "$i"
  fi
  pt+=("$pov_trace") pc+=("$pov_cpu") pw+=("$pov_wall") pr+=("$pov_rays")
  qt+=("$prism_render") qw+=("$prism_wall") qr+=("$prism_rays")
  printf '%-4s %-13s %9.3f %9s %9.3f %10d %9.3f %9.3f %10d %7.2f\n' "$i" "$order" "$pov_trace" "$pov_cpu" \
    "$pov_wall" "$pov_rays" "$prism_render" "$prism_wall" "$prism_rays" \
    "$(awk -v a="$pov_trace" -v b="$prism_render" 'BEGIN { print a / b }')"
done

m_pt="$(median "${pt[@]}")" m_pw="$(median "${pw[@]}")" m_pr="$(median "${pr[@]}")"
m_qt="$(median "${qt[@]}")" m_qw="$(median "${qw[@]}")" m_qr="$(median "${qr[@]}")"
if [[ "${pc[*]}" == *"?"* ]]; then m_pc="?"; else m_pc="$(median "${pc[@]}")"; fi
printf '%-4s %-13s %9.3f %9s %9.3f %10d %9.3f %9.3f %10d %7.2f\n' med "" "$m_pt" "$m_pc" "$m_pw" "$m_pr" \
  "$m_qt" "$m_qw" "$m_qr" "$(awk -v a="$m_pt" -v b="$m_qt" 'BEGIN { print a / b }')"

awk -v pt="$m_pt" -v pw="$m_pw" -v pr="$m_pr" -v qt="$m_qt" -v qw="$m_qw" -v qr="$m_qr" \
  -v pc="$m_pc" -v n="$runs" -v primary="$pov_primary" -v shadow="$pov_shadow" 'BEGIN {
  printf "\nPOV-Ray rays: %d = %d Rays (camera+reflected+refracted+transmitted) + %d Shadow Ray Tests\n", pr, primary, shadow
  printf "Prism rays:   %d (all kinds: camera, reflect, refract, shade1, alpha, shadow)\n", qr
  printf "render phase (median): POV-Ray trace %.3f s (%s CPU-s), Prism render %.3f s\n", pt, pc, qt
  printf "time ratio povray/prism: %.2f (render phase), %.2f (wall-clock, whole processes)\n", pt / qt, pw / qw
  povrps = pr / pt; prrps = qr / qt
  printf "rays/s: POV-Ray %.3g, Prism %.3g, Prism/POV-Ray %.2f\n", povrps, prrps, prrps / povrps
  t = pt / qt
  word = (t >= 1) ? "faster" : "slower"
  f = (t >= 1) ? t : 1 / t
  printf "ratio: prism is %.1fx %s (median of %d interleaved runs), throughput %.1fx\n", f, word, n, prrps / povrps
}'

if [ -n "$keep" ]; then
  mkdir -p "$keep"
  cp "$work/prism_1.png" "$keep/prism.png"
  cp "$work/povray_1.png" "$keep/povray.png"
  cp "$work/prism_1.json" "$keep/prism_stats.json"
  tr '\r' '\n' <"$work/povray_1.log" >"$keep/povray.log"
  if command -v oiiotool >/dev/null 2>&1; then
    oiiotool "$keep/prism.png" "$keep/povray.png" --mosaic 2x1 -o "$keep/side_by_side.png"
    oiiotool "$keep/prism.png" "$keep/povray.png" --absdiff --mulc 4 -o "$keep/diff_x4.png"
    echo "kept in $keep: prism.png, povray.png, side_by_side.png (Prism left), diff_x4.png, logs"
  else
    echo "kept in $keep: prism.png, povray.png, logs (no oiiotool: no side_by_side.png; apt-get install openimageio-tools)"
  fi
fi
