#!/usr/bin/python3
"""The results of this tree's hexdyn against an older commit's, scene by scene: the check
that a change of code moved no result beyond a tolerance.

    /usr/bin/python3 tests/regression/compare_with_base.py COMMIT [--rtol 1e-12]
        [--new build/hexdyn] [--old PATH] [--scene FILE ...] [--keep DIR]
        [--allow-new-datasets] [--ignore-layout-version]

COMMIT's hexdyn is built in build/side-COMMIT, a git worktree of the commit
(tests/regression/side_build.py; reused when it is there), unless --old names a binary. Both
binaries run each scene (default: configs/paper.yaml and every configs/robots/*_stairs.yaml
of this tree that COMMIT has too; the others are named as new), then `hexdyn replay` of
their own result, one binary after the other in one folder under the same file names (a
replay records the path of its source), the files then moved to old/ and new/ of the work
folder (--keep).
Each pair of files, old first, goes to tests/regression/compare_results.py with --rtol and
the two switches (each prints what it ignored). A run's exit status must be the same for
both binaries.

Prints one line per comparison, "identical" (every dataset equal, floats to the last bit),
"agree to rtol" or "DIFFER" with compare_results.py's lines, then a summary. Exit status
1 when a comparison fails or a run fails with one binary only.
"""

import argparse
import glob
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import side_build  # noqa: E402

COMPARE = os.path.join(HERE, "compare_results.py")
PYTHON = "/usr/bin/python3"


def default_scenes():
    """configs/paper.yaml and the shipped hexapods' stairs scenes."""
    return [os.path.join(ROOT, "configs", "paper.yaml")] + sorted(
        glob.glob(os.path.join(ROOT, "configs", "robots", "*_stairs.yaml")))


def in_commit(commit, path):
    """True when `path` (a file of this tree) exists at `commit`."""
    rel = os.path.relpath(path, ROOT)
    return subprocess.run(["git", "-C", ROOT, "cat-file", "-e", f"{commit}:{rel}"],
                          capture_output=True).returncode == 0


def run(hexdyn, args, cwd):
    """Runs `hexdyn ARGS` in cwd; returns (exit status, last line of stderr)."""
    proc = subprocess.run([hexdyn] + args, cwd=cwd, stdout=subprocess.DEVNULL,
                          stderr=subprocess.PIPE, text=True)
    lines = proc.stderr.strip().splitlines()
    return proc.returncode, lines[-1] if lines else ""


def compare(a, b, rtol, switches):
    """(verdict, lines): compare_results.py of files a and b, at rtol and at rtol 0."""
    def call(tol):
        return subprocess.run([PYTHON, COMPARE, a, b, "--rtol", repr(tol)] + switches,
                              capture_output=True, text=True)
    exact = call(0.0)
    if exact.returncode == 0:
        return "identical", exact.stdout.splitlines()[:-1]
    loose = call(rtol)
    out = (loose.stdout + loose.stderr).splitlines()
    if loose.returncode == 0:
        return f"agree to rtol {rtol:g}", out[:-1]
    return "DIFFER", out


def produce(binaries, scene, work):
    """Runs `scene` and replays its result with each binary in turn, in work/run under the
    same names (a replay records its source's path), then moves the files to work/old or
    work/new. Returns {step: (old path, new path)} for the steps both binaries completed,
    and the lines of the failures."""
    name = os.path.splitext(os.path.basename(scene))[0]
    steps = {"run": ["run", scene, "-o", f"{name}.h5"],
             "replay": ["replay", f"{name}.h5", "-o", f"{name}_replay.h5"]}
    here = os.path.join(work, "run")
    status = {}
    for which, hexdyn in binaries.items():
        for step, args in steps.items():
            status[which, step] = run(hexdyn, args, here)
        for out in os.listdir(here):
            os.replace(os.path.join(here, out), os.path.join(work, which, out))
    files, failures = {}, []
    for step, args in steps.items():
        (old, old_line), (new, new_line) = status["old", step], status["new", step]
        if old != new:
            failures.append(f"{name} {step}: exit status {old} (old) vs {new} (new): "
                            f"{new_line or old_line}")
        out = args[args.index("-o") + 1]
        paths = tuple(os.path.join(work, which, out) for which in ("old", "new"))
        if all(os.path.exists(p) for p in paths):
            files[step] = paths
        elif old == new and new != 0:
            failures.append(f"{name} {step}: both binaries failed (exit {new}): {new_line}")
    return files, failures


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("commit", help="the older commit (B)")
    ap.add_argument("--rtol", type=float, default=1e-12,
                    help="relative tolerance of compare_results.py (default %(default)g)")
    ap.add_argument("--new", default=os.path.join(ROOT, "build", "hexdyn"))
    ap.add_argument("--old", help="COMMIT's hexdyn (default: built in build/side-COMMIT)")
    ap.add_argument("--scene", action="append",
                    help="a scene to run (repeatable; default paper and the stairs scenes)")
    ap.add_argument("--keep", help="write the files to this folder (default: temporary)")
    ap.add_argument("--allow-new-datasets", action="store_true",
                    help="compare_results.py: ignore what the new files have and the old lack")
    ap.add_argument("--ignore-layout-version", action="store_true",
                    help="compare_results.py: ignore the layout version")
    args = ap.parse_args()
    if not os.access(args.new, os.X_OK):
        sys.exit(f"compare_with_base: {args.new} is not an executable (build hexdyn first)")
    old = args.old or os.path.join(side_build.checked_build(args.commit, who="compare_with_base"),
                                   "hexdyn")
    switches = [s for s, on in (("--allow-new-datasets", args.allow_new_datasets),
                                ("--ignore-layout-version", args.ignore_layout_version)) if on]
    binaries = {"old": os.path.abspath(old), "new": os.path.abspath(args.new)}
    scenes = [os.path.abspath(s) for s in (args.scene or default_scenes())]
    if not args.scene:  # a scene added since COMMIT has nothing to compare with
        new_since = [s for s in scenes if not in_commit(args.commit, s)]
        for s in new_since:
            print(f"  not compared: {os.path.relpath(s, ROOT)} is new since {args.commit}")
        scenes = [s for s in scenes if s not in new_since]
    failed = 0
    with tempfile.TemporaryDirectory(prefix="hexdyn_base_") as tmp:
        work = os.path.abspath(args.keep) if args.keep else tmp
        for folder in ("run", "old", "new"):
            os.makedirs(os.path.join(work, folder), exist_ok=True)
        print(f"compare_with_base: {args.commit} ({old}) against {args.new}, rtol {args.rtol:g}")
        for scene in scenes:
            files, failures = produce(binaries, scene, work)
            for line in failures:
                print(f"  FAILED  {line}")
            failed += len(failures)
            for step, (a, b) in files.items():
                verdict, lines = compare(a, b, args.rtol, switches)
                print(f"  {verdict:<16} {os.path.relpath(scene, ROOT)} {step}")
                for line in lines:
                    print(f"      {line}")
                failed += verdict == "DIFFER"
    total = f"{len(scenes)} scenes and their replays"
    if failed:
        print(f"compare_with_base: {failed} comparisons failed ({total})")
        return 1
    print(f"compare_with_base: {total} agree with {args.commit} to rtol {args.rtol:g}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
