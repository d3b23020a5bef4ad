#!/usr/bin/python3
"""Tests of analysis/animate.py (docs/user/animation.md#animations) against independent
computations:

  result  the paper run: frame count ceil(duration * fps) of a GIF (Pillow's n_frames) and of
          an HTML page (its embedded PNG frames); the feet the renderer draws equal
          /feet/position interpolated with numpy.interp at t0 + i / fps; the legs drawn by
          forward kinematics end at /feet/position (1e-6 m) at every sample; the HTML page
          references nothing outside itself; the terrain drawn is /terrain/y, /terrain/z; a
          file without /terrain gives one warning line; bad input gives one line, exit 2
          and no output.
  sweep   a --keep-runs sweep: --run ID draws that run (its own frame count); without
          --run, or with an unknown id, one line listing the ids, exit 2.
  mp4     an MP4 through ffmpeg has ceil(duration * fps) frames (ffprobe); skipped (exit
          77) without ffmpeg.
  replay  a one-cycle paper run and its replay (`hexdyn replay`): --replay draws two panels
          at the plan's ceil(duration * fps) frames, the plan's feet /feet/position and the
          replay's its own, each interpolated with numpy.interp at the plan's frame times
          (past the replay's end its last sample), the replay's feet green exactly where
          /contacts/normal_force > 0 at the last sample at or before the frame; --ghost
          draws the replay with the plan's feet (interpolated likewise) as ghosts,
          --ghost-trunk the plan's trunk too; a replay of another plan gives one warning
          line; --ghost without --replay, a --replay file that is no replay and a replay
          given as the plan: one line, exit 2, no output.

usage: test_animate.py CASE --hexdyn BUILD/hexdyn --source SOURCE_DIR
"""

import argparse
import base64
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np

SKIP = 77
failures = []


def check(ok, what, detail=""):
    print(f"{'ok  ' if ok else 'FAIL'} {what}{': ' + detail if detail and not ok else ''}")
    if not ok:
        failures.append(what)


def expected_frames(t, fps):
    """ceil(duration * fps), the product taken to 1e-9 (0.7000000000000001 s at 10 per second: 7)."""
    return max(1, math.ceil(round((t[-1] - t[0]) * fps, 9)))


def animate(src, *args):
    cmd = ["/usr/bin/python3", os.path.join(src, "analysis", "animate.py"), *args]
    return subprocess.run(cmd, capture_output=True, text=True)


def animate_here(*args):
    """(exit status, stderr) of animate.py's main run in this process (analysis/ on the
    path)."""
    import contextlib
    import io

    from animate import main

    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        rc = main(list(args))
    return rc, err.getvalue()


def read_time(path, group="/"):
    with h5py.File(path, "r") as f:
        return f[group]["time"][()]


def add_stairs_terrain(path, riser, tread, steps):
    """A staircase height profile written the way the result files store it (/terrain/y,
    /terrain/z, `type`), for a file written before the terrain was stored."""
    y, z = [-0.5, 0.0], [0.0, 0.0]
    for k in range(steps):
        y += [k * tread, (k + 1) * tread]
        z += [(k + 1) * riser, (k + 1) * riser]
    with h5py.File(path, "a") as f:
        if "terrain" in f:
            return False
        g = f.create_group("terrain")
        g["y"], g["z"] = np.array(y), np.array(z)
        g.attrs["type"] = "stairs"
    return True


def html_frames(text):
    m = re.search(r"var frames = \[\n(.*?)\n\];", text, re.S)
    return re.findall(r'"([A-Za-z0-9+/=]+)"', m.group(1)) if m else []


def case_result(args, d):
    sys.path.insert(0, os.path.join(args.source, "analysis"))
    import matplotlib

    matplotlib.use("Agg")
    from animate import Scene
    from animate_data import frames_of, load_motion

    bare = os.path.join(d, "paper.h5")
    subprocess.run([args.hexdyn, "run", os.path.join(args.source, "configs", "paper.yaml"),
                    "-o", bare], check=True, capture_output=True)
    full = os.path.join(d, "paper_terrain.h5")
    shutil.copy(bare, full)
    added = add_stairs_terrain(full, 0.05, 0.25, 12)
    if not added:  # the run stored its terrain: a copy without it plays a /1 file
        with h5py.File(bare, "a") as f:
            del f["terrain"]
    with h5py.File(full, "r") as f:
        t, feet = f["time"][()], f["feet/position"][()]
        base, quat = f["base/position"][()], f["base/orientation"][()]
        q, ty, tz = f["joints/position"][()], f["terrain/y"][()], f["terrain/z"][()]

    # Frame count, GIF and HTML, through the command line.
    for fps, ext in ((4.0, "gif"), (3.0, "html")):
        out = os.path.join(d, f"paper.{ext}")
        r = animate(args.source, full, "-o", out, "--fps", str(fps), "--dpi", "40")
        check(r.returncode == 0, f"animate -o .{ext} exits 0", r.stderr.strip())
        n = expected_frames(t, fps)
        if ext == "gif":
            from PIL import Image

            with Image.open(out) as im:
                got = im.n_frames
        else:
            text = open(out, encoding="utf-8").read()
            frames = html_frames(text)
            got = len(frames)
            check(all(base64.b64decode(s)[:8] == b"\x89PNG\r\n\x1a\n" for s in frames),
                  "HTML frames are embedded PNG images")
            check("http" not in text.lower() and "://" not in text, "HTML has no network "
                  "address", "found http or ://")
            refs = re.findall(r"""(?:src|href)\s*=\s*["']([^"']*)["']""", text)
            check(all(r == "" or r.startswith("data:") for r in refs),
                  "HTML src/href are embedded data only", str(refs))
            check(not re.search(r"<(link|script)[^>]*(src|href)", text),
                  "HTML loads no external script or style sheet")
        check(got == n, f".{ext} frame count = ceil(duration * fps) = {n}", f"got {got}")

    # What the renderer draws, frame by frame, against numpy.interp of the file.
    motion = load_motion(full)
    for view in ("side", "3d"):
        fps = 6.0
        frames = frames_of(motion, fps)
        times = t[0] + np.arange(expected_frames(t, fps)) / fps
        check(len(frames) == times.size and np.array_equal(frames.times, times),
              f"{view}: frame times t0 + i / fps")
        want = np.stack([[[np.interp(tf, t, feet[:, leg, c]) for c in range(3)]
                          for leg in range(feet.shape[1])] for tf in times])
        scene = Scene(motion, frames, view, 30)
        worst = 0.0
        for i in range(len(frames)):
            scene.update(i)
            for leg, line in enumerate(scene.feet):
                if view == "3d":
                    x, y, z = (np.asarray(a, dtype=float) for a in line.get_data_3d())
                    drawn = np.array([x[0], y[0], z[0]])
                    ref = want[i, leg]
                else:
                    y, z = (np.asarray(a, dtype=float) for a in line.get_data())
                    drawn, ref = np.array([y[0], z[0]]), want[i, leg, 1:]
                worst = max(worst, float(np.max(np.abs(drawn - ref))))
        check(worst <= 1e-12, f"{view}: feet drawn = /feet/position interpolated at the frame "
              "times (numpy.interp)", f"worst {worst:.3g} m")
        if view == "side":
            ty_drawn = [line for line in scene.ax.lines if line.get_label().startswith("terrain")]
            check(len(ty_drawn) == 1 and np.array_equal(ty_drawn[0].get_xdata(), ty)
                  and np.array_equal(ty_drawn[0].get_ydata(), tz),
                  "side: the terrain drawn is /terrain/y, /terrain/z")
        import matplotlib.pyplot as plt

        plt.close(scene.fig)

    # The legs by forward kinematics end at the stored feet, at every sample.
    legs = motion.skeleton(base, quat, q)
    fk_feet = np.stack([leg[:, -1, :] for leg in legs], axis=1)
    err = float(np.max(np.abs(fk_feet - feet)))
    check(err <= 1e-6, "legs by forward kinematics of /model/urdf end at /feet/position",
          f"worst {err:.3g} m")

    # No /terrain: one warning line, no terrain drawn.
    r = animate(args.source, bare, "-o", os.path.join(d, "bare.gif"), "--fps", "1",
                "--dpi", "30")
    warn = [line for line in r.stderr.splitlines() if "warning" in line]
    check(r.returncode == 0 and len(warn) == 1 and "/terrain" in warn[0],
          "file without /terrain: one warning line", r.stderr.strip())

    # Bad input: one line, exit 2, nothing written.
    for bad_args, what in (((full, "-o", os.path.join(d, "x.avi")), "unknown format"),
                           ((full, "-o", os.path.join(d, "x.gif"), "--fps", "0"), "fps 0"),
                           ((os.path.join(d, "missing.h5"), "-o", os.path.join(d, "x.gif")),
                            "missing file"),
                           ((full, "-o", os.path.join(d, "x.gif"), "--run", "000001"),
                            "--run on a result file")):
        r = animate(args.source, *bad_args)
        lines = r.stderr.strip().splitlines()
        check(r.returncode == 2 and len(lines) == 1 and not os.path.exists(bad_args[2]),
              f"bad input ({what}): one line, exit 2, no output", r.stderr.strip())
    leftovers = [n for n in os.listdir(d) if ".tmp" in n]
    check(not leftovers, "no temporary files left", str(leftovers))


def case_sweep(args, d):
    sweep = os.path.join(d, "smoke.h5")
    subprocess.run([args.hexdyn, "sweep", os.path.join(args.source, "configs", "sweeps",
                                                       "smoke.yaml"), "-o", sweep, "--keep-runs"],
                   check=True, capture_output=True)
    with h5py.File(sweep, "r") as f:
        ids = sorted(f["runs"].keys())
    check(len(ids) >= 2, "the sweep kept its runs", str(ids))
    run = ids[-1]
    out = os.path.join(d, "run.html")
    r = animate(args.source, sweep, "--run", run, "-o", out, "--fps", "4", "--dpi", "30")
    check(r.returncode == 0, "--run ID on a sweep file exits 0", r.stderr.strip())
    n = expected_frames(read_time(sweep, f"/runs/{run}"), 4.0)
    got = len(html_frames(open(out, encoding="utf-8").read())) if os.path.exists(out) else -1
    check(got == n, f"--run {run}: frame count of that run = {n}", f"got {got}")
    for extra, what in (((), "no --run"), (("--run", "999999"), "unknown id")):
        target = os.path.join(d, "none.gif")
        r = animate(args.source, sweep, *extra, "-o", target)
        lines = r.stderr.strip().splitlines()
        check(r.returncode == 2 and len(lines) == 1 and all(i in lines[0] for i in ids)
              and not os.path.exists(target),
              f"sweep file, {what}: one line listing the ids, exit 2", r.stderr.strip())


# The paper scene shortened to one gait cycle of 3.4 s (a ramp up and down, no cruise), so
# that the run and its replay take about a second.
SHORT = ("motion.cycle_durations=null", "motion.cycles=1", "motion.peak_speed=0.098",
         "motion.ramp_duration=0.8")


def interp_feet(t, feet, times):
    """numpy.interp of each foot's coordinates (T,L,3) at `times` (held at the ends)."""
    return np.stack([[[np.interp(tf, t, feet[:, leg, c]) for c in range(3)]
                      for leg in range(feet.shape[1])] for tf in times])


def drawn_side(lines):
    """(lines, 2) y, z of the first point of each line of a side view."""
    return np.array([[float(np.asarray(a, dtype=float)[0]) for a in line.get_data()]
                     for line in lines])


def case_replay(args, d):
    sys.path.insert(0, os.path.join(args.source, "analysis"))
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import to_rgba
    from animate import PHASE_COLORS, Scene
    from animate_data import frames_of, load_motion

    plan, replay = os.path.join(d, "plan.h5"), os.path.join(d, "replay.h5")
    cmd = [args.hexdyn, "run", os.path.join(args.source, "configs", "paper.yaml"), "-o", plan]
    subprocess.run(cmd + [a for s in SHORT for a in ("--set", s)], check=True,
                   capture_output=True)
    subprocess.run([args.hexdyn, "replay", plan, "-o", replay], check=True, capture_output=True)
    with h5py.File(plan, "r") as f:
        t, feet = f["time"][()], f["feet/position"][()]
    with h5py.File(replay, "r") as f:
        tr, feet_r, fn = f["time"][()], f["feet/position"][()], f["contacts/normal_force"][()]

    # Through the command line: two panels, ghosts; the plan's frames.
    fps = 2.0
    for extra, ext in (((), "gif"), (("--ghost-trunk",), "html")):
        out = os.path.join(d, f"replay.{ext}")
        r = animate(args.source, plan, "--replay", replay, *extra, "-o", out, "--fps", str(fps),
                    "--dpi", "30")
        check(r.returncode == 0 and "warning" not in r.stderr,
              f"--replay {' '.join(extra)} -o .{ext}: exit 0, no warning", r.stderr.strip())
        if ext == "gif":
            from PIL import Image

            with Image.open(out) as im:
                got = im.n_frames
        else:
            got = len(html_frames(open(out, encoding="utf-8").read()))
        n = expected_frames(t, fps)
        check(got == n, f"--replay .{ext}: the plan's frame count {n}", f"got {got}")

    # What is drawn, against numpy.interp of each file at the plan's frame times.
    motion, rep = load_motion(plan), load_motion(replay)
    frames = frames_of(motion, fps)
    times = t[0] + np.arange(expected_frames(t, fps)) / fps
    want_plan, want_rep = interp_feet(t, feet, times), interp_feet(tr, feet_r, times)
    hold = np.clip(np.searchsorted(tr, times, side="right") - 1, 0, tr.size - 1)
    green = fn[hold] > 0
    for ghost in (None, "trunk"):
        scene = Scene(motion, frames, "side", 30, (rep, frames_of(rep, times=frames.times)),
                      ghost)
        worst = {"plan": 0.0, "replay": 0.0, "ghost": 0.0}
        colours_ok = True
        for i in range(len(frames)):
            scene.update(i)
            rp = scene.panels[-1]
            worst["replay"] = max(worst["replay"],
                                  float(np.max(np.abs(drawn_side(rp.feet) - want_rep[i, :, 1:]))))
            colours_ok &= all(to_rgba(line.get_color()) == to_rgba(PHASE_COLORS[2 if g else 0])
                              for line, g in zip(rp.feet, green[i]))
            plan_lines = scene.panels[0].feet if ghost is None else rp.ghost_feet
            key = "plan" if ghost is None else "ghost"
            worst[key] = max(worst[key],
                             float(np.max(np.abs(drawn_side(plan_lines) - want_plan[i, :, 1:]))))
        what = "two panels" if ghost is None else "--ghost-trunk"
        check(len(scene.panels) == (2 if ghost is None else 1), f"{what}: panel count")
        for key in ("plan", "replay") if ghost is None else ("replay", "ghost"):
            drawn = {"plan": "the plan's feet", "replay": "the replay's feet",
                     "ghost": "the ghosts"}[key]
            stored = "the replay's" if key == "replay" else "the plan's"
            check(worst[key] <= 1e-12, f"{what}: {drawn} drawn = {stored} /feet/position "
                  "interpolated at the plan's frame times", f"worst {worst[key]:.3g} m")
        check(colours_ok, f"{what}: replay feet green where /contacts/normal_force > 0")
        if ghost is not None:
            check(rp.ghost_trunk is not None, "--ghost-trunk: the plan's trunk drawn")
        plt.close(scene.fig)

    # A replay of another plan: one warning line; bad combinations: one line, exit 2 (the
    # command's main in this process: no interpreter to start for each).
    other = os.path.join(d, "other.h5")
    shutil.copy(replay, other)
    with h5py.File(other, "a") as f:
        f["meta"].attrs["source_created_utc"] = "1999-01-01T00:00:00Z"
    rc, err = animate_here(plan, "--replay", other, "-o", os.path.join(d, "o.gif"), "--fps",
                           "1", "--dpi", "20")
    warn = [line for line in err.splitlines() if "warning" in line]
    check(rc == 0 and len(warn) == 1 and "1999" in warn[0],
          "a replay of another plan: one warning line", err.strip())
    for bad_args, what in (((plan, "--ghost"), "--ghost without --replay"),
                           ((plan, "--replay", plan), "--replay of a result file"),
                           ((replay, "--replay", replay), "a replay as the plan")):
        target = os.path.join(d, "bad.gif")
        rc, err = animate_here(*bad_args, "-o", target)
        lines = err.strip().splitlines()
        check(rc == 2 and len(lines) == 1 and not os.path.exists(target),
              f"bad input ({what}): one line, exit 2, no output", err.strip())


def case_mp4(args, d):
    if not shutil.which("ffmpeg") or not shutil.which("ffprobe"):
        print("skipped: ffmpeg/ffprobe not installed (Debian package ffmpeg)")
        return SKIP
    res = os.path.join(d, "paper.h5")
    subprocess.run([args.hexdyn, "run", os.path.join(args.source, "configs", "paper.yaml"),
                    "-o", res], check=True, capture_output=True)
    out = os.path.join(d, "paper.mp4")
    r = animate(args.source, res, "-o", out, "--fps", "5", "--dpi", "40")
    check(r.returncode == 0, "animate -o .mp4 exits 0", r.stderr.strip())
    probe = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0",
                            "-show_entries", "stream=nb_read_frames,codec_name", "-of",
                            "default=nw=1", out], capture_output=True, text=True)
    fields = dict(line.split("=", 1) for line in probe.stdout.split())
    n = expected_frames(read_time(res), 5.0)
    check(fields.get("codec_name") == "h264", "MP4 is H.264", probe.stdout)
    check(fields.get("nb_read_frames") == str(n), f"MP4 frame count = {n}", probe.stdout)
    return 0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case", choices=("result", "sweep", "mp4", "replay"))
    ap.add_argument("--hexdyn", required=True)
    ap.add_argument("--source", required=True)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as d:
        rc = {"result": case_result, "sweep": case_sweep, "mp4": case_mp4,
              "replay": case_replay}[args.case](args, d)
    if rc == SKIP:
        return SKIP
    if failures:
        print(f"{len(failures)} check(s) failed: {'; '.join(failures)}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
