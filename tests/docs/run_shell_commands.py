#!/usr/bin/python3
"""Runs every shell command the README and docs/user show, as written (ctest docs.shell_commands).

    run_shell_commands.py BUILD_DIR SOURCE_DIR WORK_DIR [--all | --list]

The commands are the lines of the ```sh blocks of README.md and of every page of docs/user/,
a line ending in a backslash joined to the next, a trailing comment removed. PLAN below holds
every one of them, each either run, run with --all only (SLOW: minutes each), or skipped with
the reason and the test that covers it instead; a command of the documents missing from PLAN, or an entry of PLAN no document shows,
fails the test, so the list stays in sync with the pages.

The commands run in document order (the README first, then docs/user/ by file name) in
WORK_DIR, a fresh folder laid out like a checkout after the main command: build/ is the build
tree, and configs/, analysis/, docs/, src/ and robots/ are links into the source. The environment has
no PYTHONPATH: the analysis scripts must find the package hexdyn by themselves, as they do for
a newcomer. Open MPI's root variables are set (the README says so for root) and matplotlib
draws off screen. A command fails the test when its exit status is not zero; its last lines
of output are printed.
"""
import os
import re
import shutil
import subprocess
import sys
import time

# What each documented command is: "run", or why it is not run here and what covers it.
PIPELINE = "a pipeline that installs packages and builds: "
# Run with --all only (ctest docs.shell_commands_all): each takes from half a minute to
# several minutes on a 2-core machine, the animations of the whole paper run and the paper
# robot's envelope (with the plot that reads it).
SLOW = "slow"
PLAN = {
    # README.md
    "bash pipelines/paper.sh": PIPELINE + "its run and figures are commands of the README, below "
                               "(results/paper/paper.h5) and pipeline tests",
    "bash pipelines/test.sh": PIPELINE + "the whole test suite, this test among it",
    "mkdir -p results/paper results/sweeps/smoke results/envelope": "run",
    "build/hexdyn run configs/paper.yaml -o results/paper/paper.h5": "run",
    "build/hexdyn run configs/paper.yaml -o wave.h5 --set gait.duty_factor=3/4 --set "
    "allocation.friction=cone": "run",
    "build/hexdyn run configs/robots/phantomx_mark4_stairs.yaml -o phantomx.h5 -v": "run",
    "build/hexdyn validate configs/paper.yaml": "run",
    "build/hexdyn validate configs/sweeps/stairs.yaml": "run",
    "mpirun -np 2 build/hexdyn sweep configs/sweeps/smoke.yaml -o results/sweeps/smoke/smoke.h5":
        "run",
    "/usr/bin/python3 analysis/plot_sweep.py results/sweeps/smoke/smoke.h5 results/sweeps/smoke":
        "run",
    "/usr/bin/python3 analysis/plot_sweep.py results/sweeps/smoke/smoke.h5 results/sweeps/smoke "
    "--x terrain.riser_height --hue gait.duty_factor --sel motion.peak_speed=0.05": "run",
    "/usr/bin/python3 analysis/animate.py results/paper/paper.h5 -o results/paper/paper.html": SLOW,
    "/usr/bin/python3 analysis/plot_grip.py results/paper/paper.h5 results/paper": "run",
    "build/hexdyn envelope configs/envelope/paper.yaml -o results/envelope/paper.h5 -v": SLOW,
    "build/hexdyn replay results/paper/paper.h5 -o results/paper/replay.h5": "run",
    "build/hexdyn replay mx64.h5 -o mx64_replay.h5": "run",
    "build/hexdyn robustness configs/paper.yaml -o results/paper/robustness.h5 --set "
    "robustness.replays=20": "run",
    "build/hexdyn --help": "run",
    "build/hexdyn run configs/paper.yaml -o mx64.h5 --set actuators.default.model=dynamixel_mx64":
        "run",
    # docs/user/robustness.md
    "mkdir -p results/robustness": "run",
    "build/hexdyn robustness configs/robustness/paper.yaml -o results/robustness/paper.h5": SLOW,
    "build/hexdyn robustness configs/paper.yaml -o results/robustness/nominal.h5 --set "
    "robustness.replays=20 -j 2": "run",
    "build/hexdyn robustness results/paper/paper.h5 -o results/robustness/stored.h5 --set "
    "robustness.replays=20 --set robustness.perturbations.friction.distribution=uniform --set "
    "robustness.perturbations.friction.low=-0.1 --set robustness.perturbations.friction.high=0":
        "run",
    "bash pipelines/robustness.sh": PIPELINE + "its quick form is the test pipeline.robustness_quick",
    # docs/user/adding-a-robot.md
    "build/hexdyn validate configs/robots/solo12_flat.yaml -v": "run",
    "build/hexdyn run configs/robots/solo12_flat.yaml -o solo12_flat.h5 -v": "run",
    "build/hexdyn run configs/robots/solo12_flat.yaml -o solo12_lseq.h5 --set "
    "'gait.phases={L1: 0, L4: 0.25, L2: 0.5, L3: 0.75}'": "run",
    "build/hexdyn run configs/robots/solo12_flat.yaml -o solo12_trot.h5 --set gait.pattern=trot "
    "--set gait.duty_factor=0.6": "run",
    "mkdir -p solo12_figures": "run",
    "/usr/bin/python3 analysis/plot_kinematics.py solo12_flat.h5 solo12_figures": "run",
    "/usr/bin/python3 analysis/animate.py solo12_flat.h5 -o solo12_flat.gif --view 3d --fps 5 "
    "--dpi 60": "run",
    "/usr/bin/python3 analysis/urdf_dynamics.py solo12_flat.h5 robots/solo12.urdf": "run",
    "mkdir -p my_robot": "run",
    "cp robots/solo12.urdf my_robot/my_robot.urdf": "run",
    "cp configs/robots/solo12_flat.yaml my_robot/flat.yaml": "run",
    "sed -i 's|../../robots/solo12.urdf|my_robot.urdf|' my_robot/flat.yaml": "run",
    "build/hexdyn validate my_robot/flat.yaml -v": "run",
    "build/hexdyn run my_robot/flat.yaml -o my_robot/flat.h5": "run",
    "PYTHONPATH=build/python /usr/bin/python3 tests/python/test_robots_dart.py build/hexdyn . "
    "my_robot/flat.yaml": "the test scripts are not in the work folder; ctest "
                          "dynamics.robots_against_dart runs the script on every shipped scene",
    "PYTHONPATH=build/python /usr/bin/python3 tests/python/test_allocation_slsqp.py build/hexdyn . "
    "my_robot/flat.yaml": "the test scripts are not in the work folder; ctest "
                          "allocation.against_slsqp runs the script on every shipped scene",
    # docs/user/animation.md
    "/usr/bin/python3 analysis/animate.py results/paper/paper.h5 -o paper.html": SLOW,
    "/usr/bin/python3 analysis/animate.py results/paper/paper.h5 -o paper.mp4 --fps 10": "run",
    "/usr/bin/python3 analysis/animate.py results/paper/paper.h5 -o paper.gif --view 3d --dpi 60":
        SLOW,
    "mkdir -p results/sweeps/smoke": "run",
    "mpirun -np 2 build/hexdyn sweep configs/sweeps/smoke.yaml -o results/sweeps/smoke/kept.h5 "
    "--keep-runs": "run",
    "/usr/bin/python3 analysis/animate.py results/sweeps/smoke/kept.h5 --run 000003 -o run3.gif":
        "run",
    "/usr/bin/python3 analysis/plot_sweep.py results/sweeps/smoke/smoke.h5 results/sweeps/smoke "
    "--metric peak_torque_gait --metric \"peak_torque[L2_femur]\"": "run",
    "/usr/bin/python3 analysis/animate.py results/paper/paper.h5 --replay results/paper/replay.h5 "
    "-o both.html": SLOW,
    "/usr/bin/python3 analysis/animate.py results/paper/paper.h5 --replay results/paper/replay.h5 "
    "--ghost -o over.gif": SLOW,
    # docs/user/configuration.md
    "build/hexdyn run configs/paper.yaml -o out.h5": "run",
    "build/hexdyn run configs/paper.yaml -o out.h5 --set gait.duty_factor=3/4": "run",
    # docs/user/designs.md
    "bash pipelines/designs.sh": PIPELINE + "pipeline.designs_quick runs its reduced form",
    "bash pipelines/designs.sh --only paper": PIPELINE + "pipeline.designs_quick",
    "bash pipelines/designs.sh --quick": PIPELINE + "pipeline.designs_quick runs the same studies",
    "build/hexdyn validate configs/designs/paper_femur_tibia.yaml": "run",
    "mpirun -np 2 build/hexdyn sweep configs/designs/paper_femur_tibia.yaml -o study.h5":
        "the full design study (minutes on 2 ranks); pipeline.designs_quick runs its reduced form "
        "and the figures of analysis/plot_designs.py",
    "/usr/bin/python3 analysis/plot_designs.py study.h5 figures/":
        "needs the full design study above; pipeline.designs_quick draws these figures",
    # docs/user/envelope.md
    "bash pipelines/envelope.sh": PIPELINE + "its envelope and plot are the commands below",
    "mkdir -p results/envelope": "run",
    "/usr/bin/python3 analysis/plot_envelope.py results/envelope/paper.h5 results/envelope --table":
        SLOW,
    # docs/user/output.md
    "/usr/bin/python3 -c 'import h5py,sys; print(h5py.File(sys.argv[1])[\"meta\"].attrs"
    "[\"input_sha256\"], end=\"\")' out.h5 | sha256sum -c": "run",
    "/usr/bin/python3 docs/gen_output_tables.py":
        "rewrites docs/user/output.md in the source tree; docs.output_tables runs its --check",
    "/usr/bin/python3 docs/gen_output_tables.py --check": "run",
    # docs/user/replay.md
    "build/hexdyn replay results/paper/paper.h5 -o results/paper/slippery.h5 --set "
    "contact.static_friction=0.15 --set contact.dynamic_friction=0.1": "run",
    "build/hexdyn replay results/paper/paper.h5 -o results/paper/open_loop.h5 --set replay.kp=0 "
    "--set replay.kd=0": "run",
    # docs/user/robots.md
    "build/hexdyn validate configs/robots/phantomx_mark4_stairs.yaml -v": "run",
    "build/hexdyn run configs/robots/kraby_stairs.yaml -o kraby.h5 -v": "run",
    "bash pipelines/robots.sh": PIPELINE + "the robots' runs are the commands above; "
                                "pipeline tests of the URDF robots cover the rest",
    # docs/user/sweeps.md
    "bash pipelines/sweep_smoke.sh": PIPELINE + "its sweep and heatmaps are commands of the README",
    "sbatch pipelines/slurm_sweep.sbatch": "needs a Slurm cluster; slurm.sweep_cancel_resubmit "
                                           "submits the job script to a private one",
    "sbatch --ntasks=64 pipelines/slurm_sweep.sbatch SWEEP.yaml results/sweeps/x/x.h5":
        "needs a Slurm cluster and 64 tasks; slurm.sweep_cancel_resubmit",
    "sbatch $HEXDYN_SHARE/pipelines/slurm_sweep.sbatch SWEEP.yaml OUT.h5":
        "needs a Slurm cluster and an installed hexdyn; install.prefix runs the installed job "
        "script",
    "cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DHEXDYN_BUILD_TESTS=OFF "
    "-DHEXDYN_BUILD_BENCHMARKS=OFF": "configures the build tree; install.prefix installs it",
    "cmake --build build -j": "builds the tree; install.prefix installs it",
    "cmake --install build --prefix /opt/hexdyn/0.1.0":
        "writes under /opt; install.prefix installs into a temporary prefix and runs it",
}

DOCS_FIRST = "README.md"
FENCE = re.compile(r"```(?:sh|bash|shell)\n(.*?)```", re.S)
COMMENT = re.compile(r"\s+#\s.*$")


def documented_commands(src):
    """(document, command) in document order: the README, then docs/user/ by name."""
    user = os.path.join(src, "docs", "user")
    docs = [DOCS_FIRST] + sorted(os.path.join("docs", "user", n) for n in os.listdir(user)
                                 if n.endswith(".md"))
    out = []
    for doc in docs:
        with open(os.path.join(src, doc), encoding="utf-8") as f:
            text = f.read()
        for block in FENCE.finditer(text):
            joined = re.sub(r"\\\n\s*", " ", block.group(1))
            for line in joined.splitlines():
                line = COMMENT.sub("", line).strip()
                if line and not line.startswith("#"):
                    out.append((doc, re.sub(r"\s+", " ", line)))
    return out


def prepare(build, src, work):
    """WORK: a fresh folder laid out like a checkout after the main command."""
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    os.symlink(os.path.abspath(build), os.path.join(work, "build"))
    for name in ("configs", "analysis", "docs", "src", "robots"):
        os.symlink(os.path.join(src, name), os.path.join(work, name))


def main():
    build, src, work = (os.path.abspath(a) for a in sys.argv[1:4])
    commands = documented_commands(src)
    shown = {c for _, c in commands}
    failures = [f"{doc}: a command missing from PLAN in {__file__}: {c}"
                for doc, c in commands if c not in PLAN]
    failures += [f"PLAN names a command no page shows: {c}" for c in PLAN if c not in shown]
    if "--list" in sys.argv:
        for doc, c in commands:
            print(f"{doc}: {PLAN.get(c, 'NOT IN PLAN')[:40]}: {c}")
        return 0
    if failures:
        print("\n".join("FAILED: " + f for f in failures))
        return 1
    prepare(build, src, work)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", MPLBACKEND="Agg")
    ran = skipped = 0
    done = set()
    for doc, command in commands:
        if command in done:
            continue
        done.add(command)
        if PLAN[command] == SLOW and "--all" in sys.argv:
            pass
        elif PLAN[command] != "run":
            skipped += 1
            continue
        start = time.monotonic()
        p = subprocess.run(["bash", "-c", "set -o pipefail; " + command], cwd=work, env=env,
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        print(f"{time.monotonic() - start:6.1f} s  exit {p.returncode}  {doc}: {command}")
        ran += 1
        if p.returncode != 0:
            tail = "\n".join(p.stdout.splitlines()[-8:])
            failures.append(f"{doc}: exit status {p.returncode}: {command}\n{tail}")
    for f in failures:
        print("FAILED: " + f)
    print(f"shell commands: {ran} run, {skipped} not run (slow without --all, or skipped with "
          "the reason in PLAN), "
          f"{len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
