#!/usr/bin/python3
"""An older commit's build beside this tree's: a git worktree of the commit in a side folder
(build/side-COMMIT by default) and a Release build of the named targets in its build/.

    /usr/bin/python3 tests/regression/side_build.py COMMIT [DIR] [--target hexdyn ...]

Used by tests/regression/compare_with_base.py (results of the commit against this tree's),
bench/compare_with_base.py (speed ratios) and bench/sweep_speed.py. A folder that is
already a checkout is reused as it is, and CMake rebuilds only what is missing or stale, so
a second call costs seconds. The compiler launcher (ccache) and the other settings of the
environment reach CMake unchanged. Prints the build folder.
"""

import argparse
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def side_folder(commit):
    """The default side folder of COMMIT: build/side-COMMIT of this tree."""
    return os.path.join(ROOT, "build", f"side-{commit}")


def checkout(commit, src):
    """COMMIT checked out at `src` as a detached git worktree, unless `src` is one already."""
    if not os.path.exists(os.path.join(src, ".git")):
        subprocess.run(["git", "-C", ROOT, "worktree", "add", "--detach", src, commit],
                       check=True, stdout=subprocess.DEVNULL)


def head_of(src):
    """The full hash of the commit checked out at `src`."""
    return subprocess.run(["git", "-C", src, "rev-parse", "HEAD"], check=True,
                          capture_output=True, text=True).stdout.strip()


def full_hash(commit):
    """COMMIT (any name git accepts) as a full hash of this repository."""
    return subprocess.run(["git", "-C", ROOT, "rev-parse", "--verify", f"{commit}^{{commit}}"],
                          check=True, capture_output=True, text=True).stdout.strip()


def build(commit, src, targets=("hexdyn",), who="side_build"):
    """Checks COMMIT out at `src` (checkout) and builds `targets` in src/build (Release).
    Returns the build folder. `who` names the caller in the progress line."""
    checkout(commit, src)
    out = os.path.join(src, "build")
    print(f"{who}: building {commit}'s {', '.join(targets)} in {out}", file=sys.stderr)
    subprocess.run(["cmake", "-S", src, "-B", out, "-DCMAKE_BUILD_TYPE=Release"], check=True,
                   stdout=subprocess.DEVNULL)
    cmd = ["cmake", "--build", out, "-j2"]
    for t in targets:
        cmd += ["--target", t]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return out


def checked_build(commit, src=None, targets=("hexdyn",), who="side_build"):
    """build() into `src` (default side_folder(commit)), refusing a folder that holds
    another commit: a reused side folder must be the commit it is named for."""
    src = src or side_folder(commit)
    if os.path.exists(os.path.join(src, ".git")) and head_of(src) != full_hash(commit):
        sys.exit(f"{who}: {src} holds {head_of(src)[:12]}, not {commit}; remove it "
                 f"(git worktree remove {src}) or name another folder")
    return build(commit, src, targets, who)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("commit")
    ap.add_argument("dir", nargs="?", help="side folder (default build/side-COMMIT)")
    ap.add_argument("--target", action="append",
                    help="a CMake target to build (repeatable; default hexdyn)")
    args = ap.parse_args()
    print(checked_build(args.commit, args.dir, tuple(args.target or ["hexdyn"])))
    return 0


if __name__ == "__main__":
    sys.exit(main())
