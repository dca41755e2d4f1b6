#!/usr/bin/env bash
# The per-type field table of docs/scene-format.md is generated: it is what
# `prism plugin fields --markdown` prints from the primitive plugins' own
# field tables (names, ranges, defaults, doc strings), placed between the
# lines `<!-- fields:begin -->` and `<!-- fields:end -->`. This script
# compares the two and fails with a diff when they differ (a plugin's field
# or doc string changed, a plugin was added), or rewrites the block with
# --update.
#
#   scripts/check_field_docs.sh PRISM [DOC]             check (CTest: docs_field_table)
#   scripts/check_field_docs.sh --update PRISM [DOC]    rewrite DOC's block
#
# PRISM is the built `prism` executable; it finds the built plugins beside
# it (PRISM_PLUGIN_PATH is ignored here, so that plugins from elsewhere do
# not end up in the docs). DOC defaults to this checkout's docs/scene-format.md.
# Exit status: 0 the docs match (or were updated), 1 they differ, 2 bad use.
set -euo pipefail

update=0
if [[ "${1:-}" == "--update" ]]; then
  update=1
  shift
fi
if [[ $# -lt 1 || $# -gt 2 ]]; then
  echo "usage: $0 [--update] PRISM [DOC]" >&2
  exit 2
fi
prism="$1"
doc="${2:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/docs/scene-format.md}"
begin='<!-- fields:begin -->'
end='<!-- fields:end -->'

if [[ $(grep -cxF "$begin" "$doc") != 1 || $(grep -cxF "$end" "$doc") != 1 ]]; then
  echo "$doc: needs exactly one line '$begin' and one line '$end'" >&2
  exit 2
fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
env -u PRISM_PLUGIN_PATH "$prism" plugin fields --markdown >"$work/generated.md"
# The lines strictly between the markers.
awk -v b="$begin" -v e="$end" '$0 == e { inside = 0 } inside { print } $0 == b { inside = 1 }' "$doc" >"$work/current.md"

if cmp -s "$work/current.md" "$work/generated.md"; then
  echo "$doc: the field table matches the plugins"
  exit 0
fi
if [[ $update == 1 ]]; then
  awk -v b="$begin" -v e="$end" -v table="$work/generated.md" '
    $0 == e { inside = 0 }
    !inside { print }
    $0 == b { inside = 1; while ((getline line < table) > 0) print line }' "$doc" >"$work/updated.md"
  cat "$work/updated.md" >"$doc"
  echo "$doc: field table updated"
  exit 0
fi
echo "$doc: the field table differs from the plugins' field tables (- docs, + plugins):"
diff -u --label docs --label plugins "$work/current.md" "$work/generated.md" || true
echo "Refresh it with: scripts/check_field_docs.sh --update $prism"
exit 1
