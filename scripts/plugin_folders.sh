# Sourced by the plugin checks (check_plugin_glsl.sh, check_no_glsl_twin.sh):
# every primitive plugin folder of the tree, as lines "<type> <folder>".
# Prism's own plugins are plugins/<type>/; the SDK's examples are folders
# under examples/ whose CMakeLists.txt calls prism_add_primitive_plugin
# (examples/primitive-plugin: the capsule), so the example an outside
# author copies is held to the same rules as the plugins in the tree.
#   plugin_folders ROOT
plugin_folders() {
  local root="$1" dir cmake type
  for dir in "$root"/plugins/*/; do
    [[ -f "$dir/CMakeLists.txt" ]] && echo "$(basename "$dir") ${dir%/}"
  done
  for cmake in "$root"/examples/*/CMakeLists.txt; do
    [[ -f "$cmake" ]] || continue
    type="$(sed -n 's/^prism_add_primitive_plugin(\([A-Za-z0-9_]*\)[ )].*/\1/p' "$cmake")"
    [[ -n "$type" ]] && echo "$type $(dirname "$cmake")"
  done
  return 0
}
