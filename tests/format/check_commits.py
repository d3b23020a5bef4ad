#!/usr/bin/python3
"""Commit messages: a subject of at most 72 characters, a blank second line, then a body.

    /usr/bin/python3 tests/format/check_commits.py [SOURCE_DIR]     # ctest format.commit_messages
    /usr/bin/python3 tests/format/check_commits.py --message FILE   # the commit-msg hook

History mode checks every commit of SOURCE_DIR's HEAD after the boundary commit BOUNDARY
(the history before it is left as it is), merges excepted (git writes their messages).
It is skipped, exit status 77 with one line saying why, outside a git checkout and when
the boundary is not in the history (a shallow clone, an export). --boundary REV checks
from another commit.

--message FILE checks one message as git hands it to .githooks/commit-msg: comment lines
(#...) and everything below git's scissors line are not part of it.

The rule, for a message's lines after trailing blank lines are dropped:
  1. line 1, the subject, is not empty and has at most 72 characters;
  2. line 2 is empty;
  3. some line after it is not blank: the body, saying why.
Exit status: 0 when every message keeps the rule; 1 otherwise, one line per broken rule,
`COMMIT: what` (the commit's short hash and subject), and how to fix the last commit.
"""
import argparse
import os
import subprocess
import sys

BOUNDARY = "00d88bfd7098f551d370916dd21b2069bdddabd0"
MAX_SUBJECT = 72
SCISSORS = "# ------------------------ >8 ------------------------"


def problems_of(message):
    """The rules `message` breaks, as short texts; [] when it keeps them all."""
    lines = message.split("\n")
    while lines and not lines[-1].strip():
        lines.pop()
    if not lines or not lines[0].strip():
        return ["empty subject"]
    out = []
    subject = lines[0]
    if len(subject) > MAX_SUBJECT:
        out.append(f"subject of {len(subject)} characters (at most {MAX_SUBJECT})")
    if len(lines) == 1:
        out.append("no body (a blank line after the subject, then why)")
        return out
    if lines[1].strip():
        out.append("second line not blank (the subject is one line, then a blank line)")
    elif not any(line.strip() for line in lines[2:]):
        out.append("no body (a blank line after the subject, then why)")
    return out


def hook_message(text):
    """The message git will record from the file the commit-msg hook is given."""
    kept = []
    for line in text.split("\n"):
        if line.startswith(SCISSORS):
            break
        if line.startswith("#"):
            continue
        kept.append(line.rstrip())
    return "\n".join(kept)


def git(root, *args):
    return subprocess.run(["git", "-C", root, *args], capture_output=True, text=True)


def check_history(root, boundary):
    if git(root, "rev-parse", "--is-inside-work-tree").stdout.strip() != "true":
        print(f"commit messages: skipped: {root} is not a git checkout")
        return 77
    full = git(root, "rev-parse", "--verify", "-q", boundary + "^{commit}").stdout.strip()
    if not full or git(root, "merge-base", "--is-ancestor", full, "HEAD").returncode != 0:
        shallow = git(root, "rev-parse", "--is-shallow-repository").stdout.strip() == "true"
        print(f"commit messages: skipped: the boundary commit {boundary[:12]} is not in the "
              f"history of HEAD{' (a shallow clone)' if shallow else ''}")
        return 77
    listing = git(root, "log", "--no-merges", "--format=%H%x00%B%x00", f"{full}..HEAD")
    if listing.returncode != 0:
        print(f"commit messages: git log failed: {listing.stderr.strip()}")
        return 1
    fields = listing.stdout.split("\0")
    bad = 0
    count = 0
    for i in range(0, len(fields) - 1, 2):
        sha, message = fields[i].strip(), fields[i + 1]
        if not sha:
            continue
        count += 1
        subject = message.split("\n")[0]
        for p in problems_of(message):
            print(f"{sha[:10]} \"{subject[:60]}\": {p}")
            bad += 1
    if bad:
        print(f"commit messages: {bad} problems in {count} commits after {full[:10]}; the "
              f"last commit is fixed with `git commit --amend`, older ones with "
              f"`git rebase -i {full[:10]}` (reword)")
        return 1
    print(f"commit messages: {count} commits after {full[:10]} have a subject of at most "
          f"{MAX_SUBJECT} characters, a blank line and a body")
    return 0


def check_file(path):
    try:
        with open(path, encoding="utf-8", errors="replace") as fh:
            message = hook_message(fh.read())
    except OSError as e:
        print(f"commit-msg: {path}: {e.strerror}")
        return 1
    problems = problems_of(message)
    for p in problems:
        print(f"commit-msg: {p}")
    if problems:
        print(f"commit-msg: the message is kept in {path}; "
              f"`git commit -e -F {path}` edits it again")
        return 1
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("root", nargs="?", default=os.path.join(os.path.dirname(__file__), "..", ".."))
    ap.add_argument("--message", metavar="FILE", help="check one message file (commit-msg hook)")
    ap.add_argument("--boundary", default=BOUNDARY, help="check the commits after this one")
    args = ap.parse_args()
    if args.message:
        return check_file(args.message)
    return check_history(os.path.abspath(args.root), args.boundary)


if __name__ == "__main__":
    sys.exit(main())
