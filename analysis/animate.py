#!/usr/bin/python3
"""Animation of a hexdyn run: the robot, the terrain and the contact forces over time.

usage: /usr/bin/python3 analysis/animate.py RESULT.h5 [--run ID] -o OUT.gif|OUT.mp4|OUT.html
                                            [--fps N] [--view side|3d] [--dpi N]
                                            [--replay REPLAY.h5 [--ghost] [--ghost-trunk]]

Draws, in each of ceil(duration * fps) frames (frame i at t0 + i / fps):
  - the robot of /model/urdf: the trunk through the hips, each leg as lines between its link
    origins (forward kinematics from /base/position, /base/orientation and /joints/position,
    interpolated linearly in /time), and the feet at /feet/position interpolated at the
    frame's time, coloured by /contacts/phase (grey swing, orange impact, green support);
  - the terrain's height profile /terrain/y, /terrain/z (none, with a warning, in a file
    without /terrain);
  - the contact forces /contacts/force (terrain on foot, world frame) as arrows from the feet;
  - the time, and the relaxed (/solver/status 1) and failed (2) samples since the previous
    frame in red; a strip below shows the phases of every leg over the whole run, the
    relaxed samples as red ticks, failed ones as black ticks, and the frame's time.

--replay REPLAY.h5 (a hexdyn-replay/3 file of `hexdyn replay RESULT.h5`) draws the replay
beside its plan RESULT.h5, two panels at the same instants (the plan's frames; a replay that
ended early holds its last state, and says so); --ghost draws the replay alone with the
plan's feet as ghosts (faded hollow markers) over it, --ghost-trunk the plan's trunk too. A
replay's feet are green where its normal contact force is positive, grey elsewhere; the
strip then shows each leg's plan above its replay. RESULT.h5 may itself be a replay file,
drawn alone.

--view side (default) looks along x at the y-z plane (the climb goes along +y); 3d is a
perspective. The output format follows the extension: .gif (Pillow), .mp4 (ffmpeg with
H.264) or .html (one self-contained page with the frames embedded as PNG and its own
player: it plays offline and references nothing outside itself). A sweep file run with
--keep-runs: --run ID chooses the kept run /runs/ID. The output is written under a
temporary name and renamed when complete.
"""

import argparse
import base64
import io
import os
import sys

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from figures import FAILED_COLOR, RELAXED_COLOR, leg_side  # first: selects the Agg backend
from animate_data import InputError, frames_of, load_motion, replay_mismatch
from animate_html import html_page
from matplotlib import animation
from matplotlib.lines import Line2D
import matplotlib.pyplot as plt
import numpy as np

PHASE_COLORS = ("#9e9e9e", "#ff7f0e", "#2ca02c")  # swing, impact, support
PHASE_NAMES = ("swing", "impact", "support")
FORCE_COLOR = "#1f77b4"
FORMATS = (".gif", ".mp4", ".html")
GHOST_ALPHA = 0.45  # the plan drawn under a replay (--ghost)


def force_scale(motion):
    """Arrow length per newton [m/N]: a third of the weight (a tripod foot's share) is drawn
    0.06 m long."""
    mass = motion.robot.total_mass or 1.0
    return 0.06 / (mass * 9.81 / 3.0)


def _limits(motion, *all_frames):
    """The box around every frame's robot (of each of `all_frames`) and the terrain."""
    pts = [p for frames in all_frames for p in
           [frames.feet.reshape(-1, 3), frames.base] + [leg.reshape(-1, 3) for leg in frames.legs]]
    pts = np.concatenate(pts)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    lo[2] = min(lo[2], float(motion.terrain[1].min())) if motion.terrain else lo[2]
    margin = 0.08
    return lo - margin, hi + margin


def _hip_ring(frames, i, order):
    """The trunk polygon of frame i: the hips (first link of each leg) in `order`, closed."""
    hips = np.stack([leg[i, 0] for leg in frames.legs])
    return np.concatenate([hips[order], hips[order[:1]]])


def _hip_order(frames):
    """The hips around their centre, in the trunk plane of frame 0."""
    hips = np.stack([leg[0, 0] for leg in frames.legs])
    c = hips.mean(axis=0)
    return np.argsort(np.arctan2(hips[:, 1] - c[1], hips[:, 0] - c[0]))


class Panel:
    """One motion drawn on one axis: the terrain, the trunk, the legs, the feet coloured by
    phase and the contact forces of its frames; optionally another motion's feet (and
    trunk) as ghosts over it."""

    def __init__(self, fig, cell, motion, frames, view, limits, scale, title=""):
        self.m, self.f, self.view, self.scale = motion, frames, view, scale
        self.lo, self.hi = limits
        lo, hi = limits
        if view == "3d":
            self.ax = fig.add_subplot(cell, projection="3d")
            self.ax.set_xlim(lo[0], hi[0])
            self.ax.set_ylim(lo[1], hi[1])
            self.ax.set_zlim(lo[2], hi[2])
            self.ax.set_box_aspect(tuple(hi - lo))
            self.ax.view_init(elev=22, azim=-35)
            self.ax.set_xlabel("x [m]")
            self.ax.set_ylabel("y [m]")
            self.ax.set_zlabel("z [m]")
        else:
            self.ax = fig.add_subplot(cell)
            self.ax.set_xlim(lo[1], hi[1])
            self.ax.set_ylim(lo[2], hi[2])
            self.ax.set_aspect("equal")
            self.ax.set_xlabel("y [m] (direction of the climb)")
            self.ax.set_ylabel("z [m]")
            self.ax.grid(alpha=0.25)
        if title:
            self.ax.set_title(title, fontsize=9)
        self._terrain()
        origin = np.zeros((1, 3))
        self.trunk = self.ax.plot(*self._xy(origin), color="0.15", lw=1.6)[0]
        n = len(frames.legs)
        left = [leg_side(k) == "left" for k in range(n)]
        self.legs = [self.ax.plot(*self._xy(origin), color="0.15" if left[k] else "0.55",
                                  lw=1.4, ls="-" if left[k] else "--")[0] for k in range(n)]
        self.feet = [self.ax.plot(*self._xy(origin), "o", ms=6, mec="k", mew=0.6)[0]
                     for k in range(n)]
        self.order = _hip_order(frames)
        self.arrows = []
        self.quiver = None
        if frames.force is not None and view != "3d":
            y0 = np.zeros(n)
            self.quiver = self.ax.quiver(y0, y0, y0, y0, angles="xy", scale_units="xy", scale=1,
                                         color=FORCE_COLOR, width=0.004, zorder=5)
        self.ghost_frames = self.ghost_feet = self.ghost_trunk = None
        self.note = None
        if motion.is_replay:  # a replay that ended early says so past its end
            self.note = self.ax.text(0.99, 0.02, "", transform=self.ax.transAxes, ha="right",
                                     fontsize=8, color=RELAXED_COLOR) if view != "3d" else \
                self.ax.text2D(0.99, 0.02, "", transform=self.ax.transAxes, ha="right",
                               fontsize=8, color=RELAXED_COLOR)

    def add_ghost(self, frames, trunk=False):
        """Draws `frames`' feet (and trunk) faded over this panel's robot, at each frame."""
        origin = np.zeros((1, 3))
        self.ghost_frames = frames
        self.ghost_order = _hip_order(frames)
        self.ghost_feet = [self.ax.plot(*self._xy(origin), "o", ms=8, mfc="none", mew=1.4,
                                        alpha=GHOST_ALPHA, zorder=6)[0] for _ in frames.legs]
        if trunk:
            self.ghost_trunk = self.ax.plot(*self._xy(origin), color="0.15", lw=1.6, ls=":",
                                            alpha=GHOST_ALPHA)[0]

    def _xy(self, pts):
        a = np.asarray(pts)
        return (a[..., 0], a[..., 1], a[..., 2]) if self.view == "3d" else (a[..., 1], a[..., 2])

    def _terrain(self):
        if not self.m.terrain:
            return
        y, z, kind = self.m.terrain
        if self.view == "3d":
            xs = np.array([self.lo[0], self.hi[0]])
            Y, X = np.meshgrid(y, xs)
            Z = np.tile(z, (2, 1))
            self.ax.plot_surface(X, Y, Z, color="0.8", alpha=0.5, linewidth=0, shade=False)
            for x in xs:
                self.ax.plot(np.full_like(y, x), y, z, color="0.4", lw=0.8)
        else:
            bottom = min(self.lo[2], float(z.min())) - 1.0
            self.ax.fill_between(y, z, bottom, color="0.85", lw=0, zorder=0)
            self.ax.plot(y, z, color="0.35", lw=1.0, zorder=1,
                         label=f"terrain ({kind})" if kind else "terrain")

    def update(self, i):
        f = self.f
        self._set(self.trunk, _hip_ring(f, i, self.order))
        for k in range(len(self.legs)):
            self._set(self.legs[k], f.legs[k][i])
            self._set(self.feet[k], f.feet[i, k][None])
            code = int(f.phase[i, k]) if f.phase is not None else 0
            self.feet[k].set_color(PHASE_COLORS[code])
            self.feet[k].set_markeredgecolor("k")
        artists = [self.trunk] + self.legs + self.feet
        if f.force is not None:
            artists += self._forces(i)
        if self.ghost_feet is not None:
            g = self.ghost_frames
            for k in range(len(self.ghost_feet)):
                self._set(self.ghost_feet[k], g.feet[i, k][None])
                code = int(g.phase[i, k]) if g.phase is not None else 0
                self.ghost_feet[k].set_markeredgecolor(PHASE_COLORS[code])
            artists += self.ghost_feet
            if self.ghost_trunk is not None:
                self._set(self.ghost_trunk, _hip_ring(g, i, self.ghost_order))
                artists.append(self.ghost_trunk)
        if self.note is not None:
            end = float(self.m.time[-1])
            ended = f.times[i] > end + 1e-9
            why = self.m.end_message
            self.note.set_text(f"replay ended at t = {end:.3f} s" + (f": {why}" if why else "")
                               if ended else "")
            artists.append(self.note)
        return artists

    def _forces(self, i):
        f = self.f
        vec = f.force[i] * self.scale
        if self.view == "3d":
            for a in self.arrows:
                a.remove()
            start = f.feet[i]
            self.arrows = [self.ax.quiver(start[:, 0], start[:, 1], start[:, 2], vec[:, 0],
                                          vec[:, 1], vec[:, 2], color=FORCE_COLOR, lw=1.2,
                                          arrow_length_ratio=0.2)]
            return []
        self.quiver.set_offsets(np.stack([f.feet[i, :, 1], f.feet[i, :, 2]], axis=1))
        self.quiver.set_UVC(vec[:, 1], vec[:, 2])
        return [self.quiver]

    def _set(self, line, pts):
        if self.view == "3d":
            line.set_data_3d(pts[:, 0], pts[:, 1], pts[:, 2])
        else:
            line.set_data(pts[:, 1], pts[:, 2])


class Scene:
    """The figure and the artists updated per frame: one panel (a run; or a replay with its
    plan's ghosts), or two (a plan and its replay, side by side), the clock, and the strip
    of the phases under them. `replay` is (Motion, Frames) of a replay at the plan's frame
    times; `ghost` None (two panels), "feet" or "trunk" (the plan's feet, and trunk)."""

    def __init__(self, motion, frames, view, dpi, replay=None, ghost=None):
        self.m, self.f, self.view = motion, frames, view
        self.replay = replay
        self.scale = force_scale(motion)
        both = replay is not None and ghost is None
        self.fig = plt.figure(figsize=(13.0 if both else 8.0, 5.6), dpi=dpi)
        grid = self.fig.add_gridspec(2, 2 if both else 1, height_ratios=(5.2, 1.0), hspace=0.28,
                                     wspace=0.12, left=0.06 if both else 0.08, right=0.97,
                                     top=0.93 if replay is None else 0.89, bottom=0.08)
        limits = _limits(motion, frames, *([replay[1]] if replay else []))
        if replay is None:
            self.panels = [Panel(self.fig, grid[0], motion, frames, view, limits, self.scale)]
        elif ghost is None:
            self.panels = [Panel(self.fig, grid[0, 0], motion, frames, view, limits, self.scale,
                                 f"plan: {os.path.basename(motion.source)}"),
                           Panel(self.fig, grid[0, 1], *replay, view, limits, self.scale,
                                 f"replay: {os.path.basename(replay[0].source)}")]
        else:
            self.panels = [Panel(self.fig, grid[0], *replay, view, limits, self.scale,
                                 f"replay: {os.path.basename(replay[0].source)}, with the "
                                 "plan's feet as ghosts")]
            self.panels[0].add_ghost(frames, trunk=ghost == "trunk")
        self.clock = self.fig.text(0.08, 0.955, "", fontsize=10, family="monospace")
        self.flag = self.fig.text(0.97, 0.955, "", fontsize=10, color=RELAXED_COLOR, ha="right")
        self._legend(ghost)
        self.strip = self.fig.add_subplot(grid[1, :] if both else grid[1])
        self._timeline()
        names = [os.path.basename(m.source) for m in [motion] + ([replay[0]] if replay else [])]
        self.fig.text(0.005, 0.005, "  ".join(names), fontsize=7, color="0.4")

    @property
    def ax(self):
        """The (first) panel's axis."""
        return self.panels[0].ax

    @property
    def feet(self):
        """The (first) panel's feet markers, one line per leg."""
        return self.panels[0].feet

    def _legend(self, ghost):
        handles = [Line2D([], [], marker="o", ls="", color=c, mec="k", label=n)
                   for c, n in zip(PHASE_COLORS, PHASE_NAMES)]
        handles += [Line2D([], [], color="0.15", label="left legs"),
                    Line2D([], [], color="0.55", ls="--", label="right legs")]
        if self.f.force is not None:
            handles.append(Line2D([], [], color=FORCE_COLOR,
                                  label=f"contact force ({self.scale * 100:.2g} m per 100 N)"))
        if ghost is not None:
            handles.append(Line2D([], [], marker="o", ls="", mfc="none", mec=PHASE_COLORS[2],
                                  mew=1.4, alpha=GHOST_ALPHA, label="plan's feet"))
        if ghost == "trunk":
            handles.append(Line2D([], [], color="0.15", ls=":", alpha=GHOST_ALPHA,
                                  label="plan's trunk"))
        if self.view == "3d":
            self.fig.legend(handles=handles, fontsize=7, loc="upper right",
                            bbox_to_anchor=(0.99, 0.93))
        else:
            self.ax.legend(handles=handles, fontsize=7, loc="upper left", ncol=2)

    def _timeline(self):
        """Each leg's impact and support phases over the run (the plan above its replay, when
        there is one), the relaxed and failed samples of the plan, a cursor."""
        ax, f = self.strip, self.f
        motions = [self.m] + ([self.replay[0]] if self.replay else [])
        ax.set_xlim(f.times[0], max([m.time[-1] for m in motions] + [f.times[-1]]))
        names = self.m.leg_names
        n = len(names)
        ax.set_ylim(-0.5, n + 0.8)
        ax.set_yticks(range(n), names[::-1])
        ax.set_xlabel("time [s]", fontsize=8)
        ax.tick_params(labelsize=7)
        height = 0.8 / len(motions)
        for k, m in enumerate(motions):
            phase, t = m.phases(), m.time
            if phase is None:
                continue
            widths = np.diff(np.append(t, t[-1]))
            for leg in range(len(names)):
                bottom = len(names) - 1 - leg + 0.4 - (k + 1) * height
                for code in (1, 2):
                    sel = phase[:, leg] == code
                    if sel.any():
                        ax.broken_barh(list(zip(t[sel], widths[sel])), (bottom, height),
                                       color=PHASE_COLORS[code], lw=0)
        if len(motions) > 1:
            ax.text(0.0, 1.02, "each leg: the plan above, the replay below", fontsize=7,
                    transform=ax.transAxes, ha="left", va="bottom")
        if self.m.has("/solver/status"):
            t = self.m.time
            status = np.asarray(self.m.data["/solver/status"])
            for code, color in ((1, RELAXED_COLOR), (2, FAILED_COLOR)):
                sel = status == code
                if sel.any():
                    ax.vlines(t[sel], n - 0.1, n + 0.7, color=color, lw=0.8)
            ax.text(1.0, 1.02, "red ticks: relaxed samples; black: failed", fontsize=7,
                    transform=ax.transAxes, ha="right", va="bottom")
        self.cursor = ax.axvline(f.times[0], color="k", lw=1.0)

    def update(self, i):
        f = self.f
        artists = [a for panel in self.panels for a in panel.update(i)]
        self.clock.set_text(f"t = {f.times[i]:7.3f} s")
        flags = []
        if f.relaxed is not None and f.relaxed[i]:
            flags.append(f"{int(f.relaxed[i])} relaxed sample(s)")
        if f.failed is not None and f.failed[i]:
            flags.append(f"{int(f.failed[i])} failed sample(s)")
        self.flag.set_text(("since the last frame: " + ", ".join(flags)) if flags else "")
        self.cursor.set_xdata([f.times[i], f.times[i]])
        return artists + [self.clock, self.flag, self.cursor]


def render(motion, frames, out, view="side", dpi=80, replay=None, ghost=None):
    """Writes the animation to `out` (format by extension) via a temporary file; `replay`
    and `ghost` as for Scene."""
    ext = os.path.splitext(out)[1].lower()
    directory = os.path.dirname(os.path.abspath(out))
    tmp = os.path.join(directory, f".{os.path.basename(out)}.tmp{os.getpid()}{ext}")
    scene = Scene(motion, frames, view, dpi, replay, ghost)
    try:
        if ext == ".html":
            pngs = []
            for i in range(len(frames)):
                scene.update(i)
                buf = io.BytesIO()
                scene.fig.savefig(buf, format="png", dpi=dpi)
                pngs.append(base64.b64encode(buf.getvalue()).decode("ascii"))
            with open(tmp, "w", encoding="utf-8") as fh:
                fh.write(html_page(pngs, frames.fps, os.path.basename(motion.source),
                                   float(frames.times[0])))
        else:
            anim = animation.FuncAnimation(scene.fig, scene.update, frames=len(frames),
                                           blit=False, repeat=False)
            if ext == ".gif":
                writer = animation.PillowWriter(fps=frames.fps)
            else:
                writer = animation.FFMpegWriter(fps=frames.fps, codec="h264",
                                                extra_args=["-pix_fmt", "yuv420p"])
            anim.save(tmp, writer=writer, dpi=dpi)
        os.replace(tmp, out)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    finally:
        plt.close(scene.fig)
    return out


def check_arguments(args):
    """InputError for an output, an option or a combination the command cannot use."""
    ext = os.path.splitext(args.output)[1].lower()
    if ext not in FORMATS:
        raise InputError(f"-o {args.output}: unknown format {ext or '(no extension)'}; "
                         f"use {', '.join(FORMATS)}")
    if not os.path.isdir(os.path.dirname(os.path.abspath(args.output))):
        raise InputError(f"-o {args.output}: no such directory")
    if args.dpi <= 0:
        raise InputError(f"--dpi must be positive, got {args.dpi}")
    if ext == ".mp4" and not animation.writers.is_available("ffmpeg"):
        raise InputError("-o .mp4 needs ffmpeg (Debian package ffmpeg), not found")
    if (args.ghost or args.ghost_trunk) and args.replay is None:
        flag = "--ghost" if args.ghost else "--ghost-trunk"
        raise InputError(f"{flag} draws a replay over its plan: give the replay with "
                         "--replay REPLAY.h5")


def load_inputs(args):
    """(motion, frames, replay, ghost): the run to draw and its frames; with --replay the
    replay (Motion, Frames at the plan's frame times) and the ghost mode (None, "feet",
    "trunk"). InputError for a file that cannot be drawn as asked."""
    motion = load_motion(args.result, args.run)
    frames = frames_of(motion, args.fps)
    if args.replay is None:
        return motion, frames, None, None
    if motion.is_replay:
        raise InputError(f"{args.result} is a replay file: give its plan as RESULT.h5 and the "
                         "replay with --replay")
    replay = load_motion(args.replay)
    if not replay.is_replay:
        raise InputError(f"--replay {args.replay} is not a hexdyn-replay/3 file (/meta schema "
                         f"{replay.meta.get('schema', 'missing')}): make one with "
                         f"`hexdyn replay {args.result} -o REPLAY.h5`")
    ghost = "trunk" if args.ghost_trunk else "feet" if args.ghost else None
    return motion, frames, (replay, frames_of(replay, times=frames.times)), ghost


def warnings_of(motion, replay):
    """The warning lines of the inputs: no terrain, feet off the forward kinematics, a
    replay of another plan."""
    lines = []
    for m in [motion] + ([replay] if replay is not None else []):
        if m.terrain is None:
            lines.append(f"{m.source} has no /terrain (a hexdyn-result/1 file): no terrain "
                         "drawn")
        err = m.fk_error()
        if err > 1e-6:
            lines.append(f"{m.source}: the feet by forward kinematics of /model/urdf differ "
                         f"from /feet/position by up to {err:.3g} m")
    if replay is not None and replay_mismatch(motion, replay):
        lines.append(replay_mismatch(motion, replay))
    return lines


def main(argv=None):
    ap = argparse.ArgumentParser(
        prog="animate.py", description=__doc__.strip().splitlines()[0],
        epilog="\n".join(__doc__.strip().splitlines()[5:]),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("result", help="a hexdyn result file, a sweep file with --keep-runs runs, "
                    "or a replay file")
    ap.add_argument("-o", "--output", required=True, help="OUT.gif, OUT.mp4 or OUT.html")
    ap.add_argument("--run", help="id of the kept run of a sweep file (/runs/ID)")
    ap.add_argument("--fps", type=float, default=25.0, help="frames per second (default 25)")
    ap.add_argument("--view", choices=("side", "3d"), default="side",
                    help="side: the y-z plane (default); 3d: a perspective")
    ap.add_argument("--dpi", type=int, default=80, help="pixels per inch of the 8 x 5.6 in "
                    "figure, 13 x 5.6 with two panels (default 80: 640 x 448 pixels)")
    ap.add_argument("--replay", metavar="REPLAY.h5", help="a replay of RESULT.h5 (hexdyn "
                    "replay), drawn beside it")
    ap.add_argument("--ghost", action="store_true", help="with --replay: the replay alone, "
                    "the plan's feet as ghosts over it")
    ap.add_argument("--ghost-trunk", action="store_true", help="as --ghost, with the plan's "
                    "trunk too")
    args = ap.parse_args(argv)
    try:
        check_arguments(args)
        motion, frames, replay, ghost = load_inputs(args)
    except InputError as e:
        print(f"animate: {e}", file=sys.stderr)
        return 2
    for line in warnings_of(motion, replay[0] if replay else None):
        print(f"animate: warning: {line}", file=sys.stderr)
    render(motion, frames, args.output, args.view, args.dpi, replay, ghost)
    print(f"animate: wrote {args.output} ({len(frames)} frames at {args.fps:g} per second)",
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
