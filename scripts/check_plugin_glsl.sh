#!/usr/bin/env bash
# Compiles every primitive plugin's GPU source the way the kernel generator
# assembles it: a header, core/glsl/prelude.glsl (the shared dialect's GLSL
# side), the library prism/sdk/modules/library.shared.glsl, each core module
# the plugin asks for with `// prism:require <module>` (once; read by
# prism-glsl-modules, the generator's own parser), the plugin's source, and a
# main() that calls <type>_intersect and <type>_surface and stores their
# results (so nothing is dead-stripped). The source is the plugin's one
# source <folder>/<type>.shared.glsl, compiled in double and in float
# (PRISM_REAL_FLOAT), or a hand-written <folder>/<type>.glsl (double). The
# plugins are those of plugins/ and the SDK's example
# (examples/primitive-plugin: the capsule), as scripts/plugin_folders.sh
# lists them.
# Each shader is compiled for OpenGL (GLSL front end, and SPIR-V for OpenGL)
# and for Vulkan (SPIR-V, checked with spirv-val when present); then all
# plugins together in one shader, which catches name clashes between them.
# Also checks the naming rule: every global name a plugin declares starts
# with its type name (torus_..., TORUS_..., Torus...), every one a core
# module declares with prism/PRISM/Prism.
#
#   scripts/check_plugin_glsl.sh [plugin ...]    (default: every plugin)
#
# Needs glslangValidator (Debian: glslang-tools) and prism-glsl-modules
# ($PRISM_GLSL_MODULES, else build/bin/prism-glsl-modules). Exits non-zero on
# any failure.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/scripts/plugin_folders.sh"
glsl_dir="$root/core/glsl"
shared_dir="$root/include/prism/sdk/modules"
modules_tool="${PRISM_GLSL_MODULES:-$root/build/bin/prism-glsl-modules}"

if ! command -v glslangValidator >/dev/null; then
  echo "check_plugin_glsl: glslangValidator not found (apt-get install glslang-tools)" >&2
  exit 1
fi
if [[ ! -x "$modules_tool" ]]; then
  echo "check_plugin_glsl: $modules_tool not found (build the target prism-glsl-modules or set PRISM_GLSL_MODULES)" >&2
  exit 1
fi
have_spirv_val=0
command -v spirv-val >/dev/null && have_spirv_val=1

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# Every plugin's folder, by type.
declare -A folder_of=()
while read -r name dir; do folder_of[$name]="$dir"; done < <(plugin_folders "$root")

if [[ $# -gt 0 ]]; then
  plugins=("$@")
else
  plugins=()
  while read -r name dir; do
    [[ -f "$dir/$name.shared.glsl" || -f "$dir/$name.glsl" ]] && plugins+=("$name")
  done < <(plugin_folders "$root")
fi

failures=0
fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}

# Modules a source asks for, in order of appearance (fails on a malformed line).
required_modules() { "$modules_tool" "$1"; }

# A plugin's GPU source: its one shared source, else a hand-written GLSL file.
plugin_source() {
  local p="$1" dir="${folder_of[$1]:-$root/plugins/$1}"
  if [[ -f "$dir/$p.shared.glsl" ]]; then
    echo "$dir/$p.shared.glsl"
  else
    echo "$dir/$p.glsl"
  fi
}

# Where core module $1 lives: a shared-dialect module or a GLSL-only one.
module_file() {
  if [[ -f "$shared_dir/$1.shared.glsl" ]]; then echo "$shared_dir/$1.shared.glsl"; else echo "$glsl_dir/$1.glsl"; fi
}

# Global names declared at column 0: #define NAME, struct NAME, and
# `[const] TYPE NAME` followed by ( = ; or [.
global_names() {
  sed -n -e 's|^#define \([A-Za-z_][A-Za-z0-9_]*\).*|\1|p' \
    -e 's|^struct \([A-Za-z_][A-Za-z0-9_]*\).*|\1|p' \
    -e 's|^\(const \)\{0,1\}[A-Za-z_][A-Za-z0-9_]* \([A-Za-z_][A-Za-z0-9_]*\) *[(=;[].*|\2|p' "$1"
}

check_names() {  # file prefix
  local file="$1" prefix="$2" name lower
  while read -r name; do
    [[ -z "$name" ]] && continue
    lower="$(tr '[:upper:]' '[:lower:]' <<<"$name")"
    if [[ "$lower" != "$prefix"* ]]; then
      fail "$file: global name '$name' does not start with '$prefix'"
    fi
  done < <(global_names "$file")
}

header() {  # precision
  echo '#version 450'
  [[ "$1" == float ]] && echo '#define PRISM_REAL_FLOAT 1'
  cat <<'EOF'
#define PRISM_BINDING_RECORDS 0
layout(local_size_x = 1) in;
EOF
}

# Appends the body of main() for one plugin, reading and writing slot `k`.
main_calls() {  # prefix index
  local p="$1" k="$2"
  cat <<EOF
  {
    uint base = ${k}u * 20u;
    PrismRay ray;
    ray.origin = real3(check_io[base + 0u], check_io[base + 1u], check_io[base + 2u]);
    ray.dir = real3(check_io[base + 3u], check_io[base + 4u], check_io[base + 5u]);
    PrismHit hit;
    bool found = ${p}_intersect(uint(check_io[base + 6u]), ray, real(check_io[base + 7u]), real(check_io[base + 8u]), hit);
    PrismSurface s;
    ${p}_surface(uint(check_io[base + 6u]), ray, hit, s);
    check_io[base + 9u] = found ? double(hit.t) : -1.0LF;
    check_io[base + 10u] = double(hit.part);
    check_io[base + 11u] = double(s.point.x + s.point.y + s.point.z);
    check_io[base + 12u] = double(s.normal.x + s.normal.y + s.normal.z);
    check_io[base + 13u] = double(s.uv.x + s.uv.y + hit.data.x + hit.data.y + hit.data.z);
  }
EOF
}

# Writes the shader for the given plugins, in precision $2, to $1.
assemble() {
  local out="$1" precision="$2" p m
  shift 2
  local -a modules=()
  for p in "$@"; do
    while read -r m; do
      [[ -z "$m" ]] && continue
      [[ " ${modules[*]-} " == *" $m "* ]] || modules+=("$m")
    done < <(required_modules "$(plugin_source "$p")")
  done
  {
    header "$precision"
    cat "$glsl_dir/prelude.glsl" "$shared_dir/library.shared.glsl"
    for m in ${modules[@]+"${modules[@]}"}; do
      if [[ ! -f "$(module_file "$m")" ]]; then
        echo "#error missing core module $m"
      else
        cat "$(module_file "$m")"
      fi
    done
    for p in "$@"; do cat "$(plugin_source "$p")"; done
    echo 'layout(std430, binding = 1) buffer CheckIo { double check_io[]; };'
    echo 'void main() {'
    local k=0
    for p in "$@"; do
      main_calls "$p" "$k"
      k=$((k + 1))
    done
    echo '}'
  } >"$out"
}

compile() {  # label shader
  local label="$1" src="$2" log="$work/log"
  if ! glslangValidator -S comp "$src" >"$log" 2>&1 || grep -qi 'warning' "$log"; then
    cat "$log" >&2
    fail "$label: OpenGL GLSL"
  fi
  if ! glslangValidator -G -S comp -o "$work/gl.spv" "$src" >"$log" 2>&1 || grep -qi 'warning' "$log"; then
    cat "$log" >&2
    fail "$label: SPIR-V for OpenGL (-G)"
  fi
  if ! glslangValidator -V -S comp --target-env vulkan1.1 -o "$work/vk.spv" "$src" >"$log" 2>&1 ||
    grep -qi 'warning' "$log"; then
    cat "$log" >&2
    fail "$label: SPIR-V for Vulkan (-V)"
  elif [[ $have_spirv_val == 1 ]] && ! spirv-val --target-env vulkan1.1 "$work/vk.spv" >"$log" 2>&1; then
    cat "$log" >&2
    fail "$label: spirv-val (Vulkan)"
  fi
}

# The prelude defines the dialect's words (real, R, OUT...), not prism names.
for m in "$glsl_dir"/*.glsl "$shared_dir"/*.shared.glsl; do
  [[ "$(basename "$m")" == prelude.glsl ]] && continue
  check_names "$m" prism
done

# Only shared sources have a float instantiation.
precisions_of() {
  local p
  for p in "$@"; do [[ "$(plugin_source "$p")" == *.shared.glsl ]] || { echo double; return; }; done
  echo double float
}

for p in "${plugins[@]}"; do
  src="$(plugin_source "$p")"
  if [[ ! -f "$src" ]]; then
    fail "$p: no $src"
    continue
  fi
  before=$failures
  check_names "$src" "$p"
  if ! modules="$(required_modules "$src")"; then
    fail "$p: malformed prism:require line"
    continue
  fi
  while read -r m; do
    [[ -z "$m" || -f "$(module_file "$m")" ]] || fail "$p: requires missing core module $m"
  done <<<"$modules"
  for precision in $(precisions_of "$p"); do
    assemble "$work/$p.comp" "$precision" "$p"
    compile "$p ($precision)" "$work/$p.comp"
  done
  [[ $failures == "$before" ]] && echo "ok: $p ($(precisions_of "$p"))"
done

if [[ ${#plugins[@]} -gt 1 ]]; then
  before=$failures
  assemble "$work/all.comp" double "${plugins[@]}"
  compile "all plugins together" "$work/all.comp"
  [[ $failures == "$before" ]] && echo "ok: all plugins in one shader (${plugins[*]})"
fi

if [[ $failures -gt 0 ]]; then
  echo "check_plugin_glsl: $failures failure(s)" >&2
  exit 1
fi
echo "check_plugin_glsl: every plugin's GLSL compiles for OpenGL and Vulkan"
