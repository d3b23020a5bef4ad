#!/usr/bin/python3
"""The robot descriptions in robots/ are the published files: every row of robots/README.md
that names a git blob gives the hash git computes for the upstream file, and the copy here
must hash to the same (sha1 of "blob <size>\\0" followed by the bytes, as `git hash-object`).

usage: /usr/bin/python3 tests/robots/check_provenance.py [ROBOTS_DIR]

Exit status 1, one line per file, when a copy differs or a named file or licence is missing.
"""

import hashlib
import os
import re
import sys


def blob_hash(path):
    with open(path, "rb") as f:
        data = f.read()
    return hashlib.sha1(b"blob %d\0" % len(data) + data).hexdigest()


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "robots")
    readme_path = os.path.join(root, "README.md")
    with open(readme_path, encoding="utf-8") as f:
        readme = f.read()
    rows = re.findall(r"^\| `([^`]+)` \|.*\(git blob ([0-9a-f]{40})\).*$", readme, re.M)
    licences = re.findall(r"`(licenses/[^`]+)`", readme)
    bad = []
    for name, expected in rows:
        path = os.path.join(root, name)
        if not os.path.isfile(path):
            bad.append(f"robots/{name}: named in robots/README.md, missing")
        elif blob_hash(path) != expected:
            bad.append(f"robots/{name}: git blob {blob_hash(path)}, the published file's is {expected}")
    for lic in licences:
        if not os.path.isfile(os.path.join(root, lic)):
            bad.append(f"robots/{lic}: named in robots/README.md, missing")
    if not rows:
        bad.append("robots/README.md: no row names a git blob")
    for line in bad:
        print(line, file=sys.stderr)
    if not bad:
        print(f"robots: {len(rows)} descriptions as published, {len(set(licences))} licence texts")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
