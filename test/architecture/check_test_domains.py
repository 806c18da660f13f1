#!/usr/bin/env python3
"""Every DDS domain id a test gives its processes belongs to one test source file.

ctest runs the tests two at a time, so two files that fly processes on the same domain hear each
other's samples: a scan-only test's driver on domain 196 fed 50 foreign scans into the odometry
replay's matcher on 196 (test_carmen_replay, 2026-11-27). The ids are found where the tests give
them: `k...Domain = N` constants, `fly(N, ...)`, `Participant name(N, ...)`,
`ScanCollector name(N)` and `node_argv("process", N, ...)`. Usage: check_test_domains.py SOURCE_DIR
"""
import pathlib
import re
import sys

PATTERNS = [
    re.compile(r"\bk\w*Domain\w*\s*=\s*(\d+)\b"),
    re.compile(r"\bfly\(\s*(\d+)\s*,"),
    re.compile(r"\bParticipant\s+\w+\(\s*(\d+)\s*,"),
    re.compile(r"\bScanCollector\s+\w+\(\s*(\d+)\s*\)"),
    re.compile(r"\bnode_argv\(\s*\"\w+\"\s*,\s*(\d+)\s*[,)]"),
]


def domains_of(path, name):
    found = {}
    for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
        for pattern in PATTERNS:
            for match in pattern.finditer(line):
                found.setdefault(int(match.group(1)), f"{name}:{number}")
    return found


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: check_test_domains.py SOURCE_DIR")
    root = pathlib.Path(sys.argv[1])
    owners = {}
    for path in sorted((root / "test").rglob("*")):
        if path.suffix in (".cpp", ".hpp"):
            for domain, where in domains_of(path, path.relative_to(root)).items():
                owners.setdefault(domain, []).append(where)
    shared = {d: w for d, w in owners.items() if len(w) > 1}
    for domain, where in sorted(shared.items()):
        print(f"DDS domain {domain} is given in more than one test file: {', '.join(where)}")
    bad = [d for d in owners if not 0 <= d <= 232]
    for domain in sorted(bad):
        print(f"DDS domain {domain} is outside 0-232: {', '.join(owners[domain])}")
    if shared or bad:
        sys.exit(1)
    print(f"{len(owners)} DDS domains, each in one test file")


if __name__ == "__main__":
    main()
