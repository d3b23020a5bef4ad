#!/usr/bin/python3
"""Runs the Python sessions the README and docs/user/output.md show, from a sweep to a
plot and reading a result, on real files (ctest docs.python_sessions).

    run_python_sessions.py HEXDYN SOURCE_DIR WORK_DIR

Writes WORK_DIR/results/sweeps/smoke/smoke.h5 with `HEXDYN sweep configs/sweeps/smoke.yaml
--keep-runs` (the file pipelines/sweep_smoke.sh writes) and WORK_DIR/results/paper/paper.h5
with `HEXDYN run configs/paper.yaml`, then runs, in WORK_DIR, the first python code block
after each document's marker line, with matplotlib's Agg back end. Fails when a block is
missing, raises, or (the README's) writes no cot.png.
"""
import os
import re
import subprocess
import sys

# (document, marker line, figure the session must write)
FRONT_DOOR = os.path.join(".", "README.md")
SESSIONS = [(FRONT_DOOR, "From a sweep to a plot", "cot.png"),
            ("docs/user/output.md", "From a sweep to a plot in Python", None),
            ("docs/user/output.md", "Reading it in Python", None),
            ("docs/user/output.md", "**Selecting at an event time.**", None)]


def block_after(text, marker):
    at = text.find(marker)
    if at < 0:
        return None
    m = re.compile(r"```python\n(.*?)```", re.S).search(text, at)
    return m.group(1) if m else None


def main():
    hexdyn, src, work = sys.argv[1:4]
    out = os.path.join(work, "results", "sweeps", "smoke")
    os.makedirs(out, exist_ok=True)
    target = os.path.join(out, "smoke.h5")
    if os.path.exists(target):
        os.remove(target)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               MPLBACKEND="Agg")
    subprocess.run([hexdyn, "sweep", os.path.join(src, "configs/sweeps/smoke.yaml"), "-o", target,
                    "--keep-runs"], check=True, env=env, stderr=subprocess.DEVNULL)
    paper = os.path.join(work, "results", "paper")
    os.makedirs(paper, exist_ok=True)
    subprocess.run([hexdyn, "run", os.path.join(src, "configs/paper.yaml"), "-o",
                    os.path.join(paper, "paper.h5")], check=True, env=env,
                   stderr=subprocess.DEVNULL)
    failures = 0
    for doc, marker, figure in SESSIONS:
        with open(os.path.join(src, doc), encoding="utf-8") as f:
            code = block_after(f.read(), marker)
        if code is None:
            print(f"FAILED: {doc}: no ```python block after '{marker}'")
            failures += 1
            continue
        if figure and os.path.exists(os.path.join(work, figure)):
            os.remove(os.path.join(work, figure))
        p = subprocess.run([sys.executable, "-c", code], cwd=work, env=env, capture_output=True,
                           text=True)
        if p.returncode != 0:
            print(f"FAILED: {doc}: the session raised:\n{p.stderr.strip()}")
            failures += 1
        elif figure and not os.path.getsize(os.path.join(work, figure)) > 0:
            print(f"FAILED: {doc}: the session drew no {figure}")
            failures += 1
        else:
            print(f"{doc}: the session after '{marker}' runs")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
