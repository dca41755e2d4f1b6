#!/usr/bin/env bash
# Fails when a file of the project refers to a path outside the repository:
# the scene format and the numerics are documented in docs/scene-format.md
# and docs/numerics.md, and nothing in the tree may send a reader (or a
# build) to a folder beside the checkout that a clone does not have.
#
# Files checked: the tracked ones (`git ls-files`) when the tree is a git
# checkout, else every file under the source tree except build outputs
# (build*/, out/) and version-control folders. Binary files are skipped.
# Each offending line is printed as file:line:text.
#
#   scripts/check_self_contained.sh [ROOT]    (default: this script's checkout)
#
# Exits 0 when no file refers outside, 1 when some do.
set -euo pipefail

root="${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}"
cd "$root"

# The pattern is assembled from pieces so that this file does not match it.
outside="sha""red"
pattern="${outside}/(spec|notes)|\.\./${outside}([^A-Za-z0-9_.-]|\$)"

list_files() {
  if command -v git >/dev/null && git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    git ls-files -z
  else
    find . \( -name .git -o -path './build*' -o -path ./out \) -prune -o -type f -print0 | sed -z 's|^\./||'
  fi
}

offending="$(mktemp)"
trap 'rm -f "$offending"' EXIT
# Only regular files that exist (a tracked file may be deleted in the work tree).
list_files | while IFS= read -r -d '' file; do
  [[ -f "$file" && ! -L "$file" ]] && printf '%s\0' "$file"
done | xargs -0 -r grep -n -I -E -H -e "$pattern" -- >"$offending" || true

if [[ -s "$offending" ]]; then
  cat "$offending"
  echo "check_self_contained: $(wc -l <"$offending") line(s) refer to a path outside the repository;" \
       "point them at docs/scene-format.md or docs/numerics.md instead" >&2
  exit 1
fi
echo "check_self_contained: no file refers to a path outside the repository"
