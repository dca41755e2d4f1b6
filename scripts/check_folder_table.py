#!/usr/bin/env python3
"""docs/architecture.md's folder table matches the tree.

The table is the rows of its "## Folders" section whose first cell is a
`folder/`. The check fails when
  - a folder it lists does not exist (`<type>`, `<name>`: no folder there);
  - a top-level folder of the repository is not listed, itself or through a
    folder inside it (`tests/` through `tests/core/`, ...);
  - the table lists folders inside a folder (tests/, apps/prism/, core/, ...)
    but not every folder there: a new tests/<topic>/ needs its row.
The tree is the tracked files (`git ls-files`) in a git checkout, else every
folder but build outputs (build*/, out/) and .git.

    scripts/check_folder_table.py [ROOT]    (CTest: docs_folder_table; default: this checkout)

Exit status: 0 the table matches, 1 it does not, 2 no table found.
"""
import os
import re
import subprocess
import sys

DOC = "docs/architecture.md"


def listed_folders(text):
    """The table's folders, without their trailing '/'."""
    section = re.search(r"^## Folders\n(.*?)(?=^## |\Z)", text, re.S | re.M)
    if not section:
        return []
    return re.findall(r"^\| `([^`]*)/` \|", section.group(1), re.M)


def tracked_files(root):
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-z"], capture_output=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return None
    return [f for f in out.decode().split("\0") if f]


def tree_folders(root):
    files = tracked_files(root)
    if files is not None:
        return {"/".join(parts[:i]) for parts in (f.split("/") for f in files) for i in range(1, len(parts))}
    folders = set()
    for path, dirs, _ in os.walk(root):
        rel = os.path.relpath(path, root)
        dirs[:] = [d for d in dirs if d != ".git" and not (rel == "." and (d.startswith("build") or d == "out"))]
        folders.update(os.path.normpath(os.path.join(rel, d)) for d in dirs)
    return folders


def pattern(entry):
    """A listed entry as a regular expression over folder paths (`<type>`: any one folder name)."""
    return re.compile("".join("[^/]+" if part.startswith("<") else re.escape(part)
                              for part in re.split(r"(<[^>]*>)", entry)))


def problems(listed, folders):
    patterns = [pattern(entry) for entry in listed]

    def is_listed(folder):  # itself, or through a folder inside it
        return any(p.fullmatch(folder) for p in patterns) or any(e.startswith(folder + "/") for e in listed)

    for entry, p in zip(listed, patterns):
        if not any(p.fullmatch(f) for f in folders):
            yield f"the folder table lists `{entry}/`, which does not exist"
    for folder in sorted(f for f in folders if "/" not in f):
        if not is_listed(folder):
            yield f"the top-level folder `{folder}/` is missing from the folder table"
    parents = sorted({entry.rsplit("/", 1)[0] for entry in listed if "/" in entry})
    for parent in parents:
        parent_pattern = pattern(parent)
        for folder in sorted(folders):
            head = folder.rpartition("/")[0]
            if head and parent_pattern.fullmatch(head) and not is_listed(folder):
                yield f"`{folder}/` is missing from the folder table (it lists other folders of `{parent}/`)"


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    with open(os.path.join(root, DOC), encoding="utf-8") as f:
        listed = listed_folders(f.read())
    if not listed:
        print(f"check_folder_table: no folder table in {DOC} (rows '| `folder/` | ... |' under '## Folders')",
              file=sys.stderr)
        return 2
    found = list(problems(listed, tree_folders(root)))
    for problem in found:
        print(f"{DOC}: {problem}", file=sys.stderr)
    if found:
        print(f"check_folder_table: {len(found)} mismatch(es) between {DOC}'s folder table and the tree",
              file=sys.stderr)
        return 1
    print(f"check_folder_table: the {len(listed)} folders of {DOC}'s table exist and cover the tree")
    return 0


if __name__ == "__main__":
    sys.exit(main())
