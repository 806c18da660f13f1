#!/usr/bin/env python3
"""Checks every #include under src/ and components/ against the table of docs/architecture.md
("Folders and what they may include"): a file may include its own folder and the folders named
in its row, nothing else. Prints each include that breaks the table (file:line, what it
includes, what its folder may include) and exits 1 when there is one; 0 and a count otherwise.

usage: check_includes.py REPO_ROOT
"""
import pathlib
import re
import sys

TABLE_HEADER = "| folder | holds | may include |"
QUOTED = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
ANGLED_GENERATED = re.compile(r"^\s*#\s*include\s+<(msg/[^>]+)>")


def read_table(doc):
    """{folder: set of folders it may include}, from the table under TABLE_HEADER."""
    lines = doc.read_text(encoding="utf-8").splitlines()
    try:
        start = lines.index(TABLE_HEADER)
    except ValueError:
        sys.exit(f"{doc}: no table with the header '{TABLE_HEADER}'")
    rules = {}
    for number, line in enumerate(lines[start + 2 :], start + 3):
        if not line.startswith("|"):
            break
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) != 3:
            sys.exit(f"{doc}:{number}: expected 3 cells, found {len(cells)}")
        folder = cells[0].strip("`")
        allowed = set(re.findall(r"`([^`]+)`", cells[2]))
        rules[folder] = allowed | {folder}
    if not rules:
        sys.exit(f"{doc}: the table under '{TABLE_HEADER}' has no rows")
    return rules


def folder_of(path, rules):
    """The table's row a file belongs to: the longest folder that contains it."""
    matches = [f for f in rules if path.startswith(f)]
    return max(matches, key=len) if matches else None


def included_folder(root, including, name):
    """The folder an include names: src/X/ or components/ for "X/...", the file's own for a bare
    name, idl/ for the generated <msg/...> types; None for a path the tree does not hold."""
    if name.startswith("msg/"):
        return "idl/"
    first = name.split("/")[0]
    if "/" not in name:
        return None  # beside the including file: its own folder
    if (root / "src" / first).is_dir():
        return f"src/{first}/"
    if (root / "components" / first).is_dir():
        return "components/"
    if (root / including).parent.joinpath(name).exists():
        return None  # relative to the including file
    return "?"


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    root = pathlib.Path(sys.argv[1]).resolve()
    rules = read_table(root / "docs" / "architecture.md")
    broken = []
    checked = 0
    for source in sorted(list((root / "src").rglob("*")) + list((root / "components").rglob("*"))):
        if source.suffix not in (".cpp", ".hpp", ".h") or not source.is_file():
            continue
        relative = source.relative_to(root).as_posix()
        own = folder_of(relative, rules)
        if own is None:
            broken.append(f"{relative}: its folder has no row in the table")
            continue
        for number, line in enumerate(source.read_text(encoding="utf-8").splitlines(), 1):
            match = QUOTED.match(line) or ANGLED_GENERATED.match(line)
            if not match:
                continue
            checked += 1
            target = included_folder(root, relative, match.group(1))
            if target is None or target in rules[own]:
                continue
            allowed = ", ".join(sorted(rules[own]))
            broken.append(
                f"{relative}:{number}: includes {match.group(1)} ({target}); "
                f"{own} may include {allowed}"
            )
    for line in broken:
        print(line)
    print(f"architecture: {checked} includes checked against docs/architecture.md, "
          f"{len(broken)} breaking it")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
