#!/usr/bin/env bash
# The installed headers are exactly the folder include/prism/ of the tree:
# every file of it, byte for byte, and nothing else.
#
#   scripts/check_installed_headers.sh BUILD SOURCE    (CTest: installed_headers)
#
# Two checks, neither of which needs anything built (the sanitizer run
# builds only the unit suite, not everything `cmake --install` copies):
#   1. the build's install scripts put nothing under <prefix>/include but
#      the one rule cmake/PrismPackage.cmake declares, the folder
#      SOURCE/include/prism (a header installed by a rule of its own, as
#      view_window.hpp once was from apps/, fails here);
#   2. that rule, run alone (its install component, "headers") into a fresh
#      prefix, yields the same files as SOURCE/include, byte for byte.
# Exit status: 0 equal, 1 they differ, 2 bad use.
set -euo pipefail

if [[ $# -ne 2 ]]; then
  echo "usage: $0 BUILD SOURCE" >&2
  exit 2
fi
build="$1"
source="$2"
if [[ ! -f "$build/cmake_install.cmake" ]]; then
  echo "check_installed_headers: $build is not a configured build folder (no cmake_install.cmake)" >&2
  exit 2
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# 1. Every install rule whose destination is under include/.
find "$build" -name cmake_install.cmake -print0 |
  xargs -0 grep -h 'file(INSTALL DESTINATION "${CMAKE_INSTALL_PREFIX}/include' >"$work/rules.txt" || true
expected="file(INSTALL DESTINATION \"\${CMAKE_INSTALL_PREFIX}/include\" TYPE DIRECTORY FILES \"$source/include/prism\")"
if [[ "$(sed 's/^ *//' "$work/rules.txt")" != "$expected" ]]; then
  echo "check_installed_headers: the install rules into include/ are not just include/prism/ installed whole:" >&2
  cat "$work/rules.txt" >&2
  exit 1
fi

# 2. What that rule installs.
cmake --install "$build" --component headers --prefix "$work/prefix" >"$work/install.log"
if ! diff -r "$source/include" "$work/prefix/include"; then
  echo "check_installed_headers: the installed include/ differs from $source/include (diff above)" >&2
  exit 1
fi
echo "check_installed_headers: the installed headers are include/prism/ ($(find "$source/include" -type f | wc -l) files)"
