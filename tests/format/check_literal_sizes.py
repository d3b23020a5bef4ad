#!/usr/bin/python3
"""No robot size written as a number in the Python layer (ctest format.literal_sizes): the
legs and joints of a robot are its file's (/model/leg_names, /model/joint_names; a sweep's
/joint_names; hexdyn.leg_names, joint_names, leg_joints), so a literal 6 (legs), 18 (joints)
or 24 (coordinates) of the paper hexapod used as a size is a script that draws or checks a
hexapod only. Every Python file under analysis/ and bindings/python/hexdyn/ of SOURCE_DIR is
read, docstrings and comments included (a shape "(T, 18)" in a docstring is wrong for other
robots too), and these are flagged:

    range(6), range(18), range(24)             loops over legs, joints, coordinates
    (6, 3), reshape(..., 6, 3)                 a leg-by-xyz shape
    np.full(18 / np.zeros(6 / ...              arrays of a count
    == 6, != 6, == 18, ... (also <, >)         comparisons with a count
    18, 24 anywhere else                       (not in 1e-18, 0.18, 18.5, x18)

ALLOWED lists the exceptions, each a (file, text of the line, reason) whose reason says why
the number there is no robot size; an entry that matches nothing is reported.

    check_literal_sizes.py SOURCE_DIR           exit 0 clean, 1 with findings (FILE:LINE: ...)
    check_literal_sizes.py --self-test          the checker on planted examples
"""

import os
import re
import sys
import tempfile

FOLDERS = ("analysis", os.path.join("bindings", "python", "hexdyn"))
COUNTS = r"(?:6|18|24)"
NUMBER_EDGE = r"(?<![\w.])(?<![eE][-+])"  # not part of a name, a decimal or an exponent
PATTERNS = (
    (re.compile(rf"\brange\(\s*{COUNTS}\s*\)"), "a loop over a fixed count"),
    (re.compile(r"\(\s*6\s*,\s*3\s*\)"), "a (legs, xyz) shape of six legs"),
    (re.compile(r"\breshape\(.*\b6\s*,\s*3\b"), "a reshape to six legs"),
    (re.compile(rf"\bnp\.(?:full|zeros|ones|empty|arange)\(\s*\(?\s*{COUNTS}\b"),
     "an array of a fixed count"),
    (re.compile(rf"(?:[=!]=|[<>]=?)\s*{COUNTS}(?![\w.])"), "a comparison with a fixed count"),
    (re.compile(rf"{NUMBER_EDGE}(?:18|24)(?![\w.])"), "18 or 24, the paper robot's joints "
                                                      "or coordinates"),
)
# (file relative to SOURCE_DIR, text the line contains, why the number is no robot size).
# Empty today: every number the patterns catch in these folders was a size. An entry that
# matches no line of its file is reported (a stale exception hides nothing).
ALLOWED = ()


def allowed(rel, line, allow):
    return any(rel == f and text in line for f, text, _ in allow)


def findings_of(rel, text, allow=ALLOWED):
    """FILE:LINE: messages of one file's text (`rel` its path below SOURCE_DIR)."""
    out = []
    for n, line in enumerate(text.splitlines(), 1):
        if allowed(rel, line, allow):
            continue
        for pattern, what in PATTERNS:
            m = pattern.search(line)
            if m:
                out.append(f"{rel}:{n}: {m.group(0).strip()!r}: {what}; take the size from "
                           f"the file (hexdyn.leg_names, joint_names, leg_joints): {line.strip()}")
                break
    return out


def python_files(root):
    for folder in FOLDERS:
        base = os.path.join(root, folder)
        for dirpath, _, names in os.walk(base):
            for name in sorted(names):
                if name.endswith(".py"):
                    path = os.path.join(dirpath, name)
                    yield os.path.relpath(path, root).replace(os.sep, "/"), path


def check(root, allow=ALLOWED):
    found, used = [], set()
    for rel, path in python_files(root):
        with open(path, encoding="utf-8") as f:
            text = f.read()
        found += findings_of(rel, text, allow)
        used |= {(a, b) for a, b, _ in allow if a == rel and b in text}
    found += [f"{a}: allow-list entry {b!r} ({why}) matches no line"
              for a, b, why in allow if (a, b) not in used]
    return found


def self_test():
    """Each planted size is flagged; the numbers that are no size are not; a tree with a
    planted size fails the check of a folder."""
    flagged = ["for leg in range(6):", "tau.reshape(len(t), 6, 3)", "out = np.full(18, np.nan)",
               "if len(feet) != 6:", "assert n == 18", "shape = (T, 24)", "x = F[:, :18]",
               "np.zeros((6, 3))", "# (T, 18) torques"]
    clean = ["eps = 1e-18", "y = 0.18", "z = 18.5", "name = 'x18'", "for leg in range(n):",
             "tau.reshape(len(t), n, 3)", "k = 3 * leg + 16", "ax.plot(t, y, ms=6)"]
    bad = [t for t in flagged if not findings_of("analysis/x.py", t)]
    bad += [t for t in clean if findings_of("analysis/x.py", t)]
    allow = (("analysis/x.py", "secrets.token_hex(24)", "24 random bytes, no robot size"),)
    if findings_of("analysis/x.py", "s = secrets.token_hex(24)", allow) or \
            not findings_of("analysis/y.py", "s = secrets.token_hex(24)", allow):
        bad.append("an allow-list entry applies to its own file only")
    with tempfile.TemporaryDirectory() as d:
        os.makedirs(os.path.join(d, "analysis"))
        with open(os.path.join(d, "analysis", "planted.py"), "w") as f:
            f.write("import numpy as np\n\n\ndef legs():\n    return np.zeros((6, 3))\n")
        if len(check(d)) != 1:
            bad.append("a planted file in analysis/ is not flagged once")
        stale = (("analysis/planted.py", "range(18)", "nothing of the kind"),)
        if not any("matches no line" in f for f in check(d, stale)):
            bad.append("a stale allow-list entry is not reported")
    for t in bad:
        print(f"check_literal_sizes self-test: wrong verdict on {t!r}", file=sys.stderr)
    cases = len(flagged) + len(clean) + 3
    print(f"check_literal_sizes self-test: {cases - len(bad)} of {cases} cases right")
    return 1 if bad else 0


def main(argv):
    if argv == ["--self-test"]:
        return self_test()
    if len(argv) != 1 or not os.path.isdir(argv[0]):
        print(__doc__.strip().splitlines()[-2].strip(), file=sys.stderr)
        return 2
    found = check(argv[0])
    for line in found:
        print(line)
    if found:
        print(f"check_literal_sizes: {len(found)} literal size(s) in "
              f"{', '.join(FOLDERS)}", file=sys.stderr)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
