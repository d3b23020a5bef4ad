#!/usr/bin/python3
"""Animation of a hexdyn run: the robot, the terrain and the contact forces over time.

usage: /usr/bin/python3 analysis/animate.py RESULT.h5 [--run ID] -o OUT.gif|OUT.mp4|OUT.html
                                            [--fps N] [--view side|3d] [--dpi N]

Draws, in each of ceil(duration * fps) frames (frame i at t0 + i / fps):
  - the robot of /model/urdf: the trunk through the hips, each leg as lines between its link
    origins (forward kinematics from /base/position, /base/orientation and /joints/position,
    interpolated linearly in /time), and the feet at /feet/position interpolated at the
    frame's time, coloured by /contacts/phase (grey swing, orange impact, green support);
  - the terrain's height profile /terrain/y, /terrain/z (none, with a warning, in a file
    without /terrain);
  - the contact forces /contacts/force (terrain on foot, world frame) as arrows from the feet;
  - the time, and the relaxed (/solver/status 1) and failed (2) samples since the previous
    frame in red; a strip below shows the phases of the six legs over the whole run, the
    relaxed samples as red ticks, failed ones as black ticks, and the frame's time.

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

from figures import FAILED_COLOR, RELAXED_COLOR  # first: selects the Agg backend
from animate_data import InputError, frames_of, load_motion
from animate_html import html_page
from matplotlib import animation
from matplotlib.lines import Line2D
import matplotlib.pyplot as plt
import numpy as np

PHASE_COLORS = ("#9e9e9e", "#ff7f0e", "#2ca02c")  # swing, impact, support
PHASE_NAMES = ("swing", "impact", "support")
FORCE_COLOR = "#1f77b4"
FORMATS = (".gif", ".mp4", ".html")


def force_scale(motion):
    """Arrow length per newton [m/N]: a third of the weight (a tripod foot's share) is drawn
    0.06 m long."""
    mass = motion.robot.total_mass or 1.0
    return 0.06 / (mass * 9.81 / 3.0)


def _limits(motion, frames):
    pts = [frames.feet.reshape(-1, 3), frames.base] + [leg.reshape(-1, 3) for leg in frames.legs]
    pts = np.concatenate(pts)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    lo[2] = min(lo[2], float(motion.terrain[1].min())) if motion.terrain else lo[2]
    margin = 0.08
    return lo - margin, hi + margin


class Scene:
    """The figure and the artists updated per frame."""

    def __init__(self, motion, frames, view, dpi):
        self.m, self.f, self.view = motion, frames, view
        self.scale = force_scale(motion)
        self.fig = plt.figure(figsize=(8.0, 5.6), dpi=dpi)
        grid = self.fig.add_gridspec(2, 1, height_ratios=(5.2, 1.0), hspace=0.28,
                                     left=0.08, right=0.97, top=0.93, bottom=0.08)
        lo, hi = _limits(motion, frames)
        self.lo, self.hi = lo, hi
        if view == "3d":
            self.ax = self.fig.add_subplot(grid[0], projection="3d")
            self.ax.set_xlim(lo[0], hi[0])
            self.ax.set_ylim(lo[1], hi[1])
            self.ax.set_zlim(lo[2], hi[2])
            self.ax.set_box_aspect(tuple(hi - lo))
            self.ax.view_init(elev=22, azim=-35)
            self.ax.set_xlabel("x [m]")
            self.ax.set_ylabel("y [m]")
            self.ax.set_zlabel("z [m]")
            self.p = lambda a: (a[..., 0], a[..., 1], a[..., 2])
        else:
            self.ax = self.fig.add_subplot(grid[0])
            self.ax.set_xlim(lo[1], hi[1])
            self.ax.set_ylim(lo[2], hi[2])
            self.ax.set_aspect("equal")
            self.ax.set_xlabel("y [m] (direction of the climb)")
            self.ax.set_ylabel("z [m]")
            self.ax.grid(alpha=0.25)
            self.p = lambda a: (a[..., 1], a[..., 2])
        self._terrain()
        style = {"color": "0.15", "lw": 1.6}
        self.trunk = self.ax.plot(*self._xy(np.zeros((1, 3))), **style)[0]
        self.legs = [self.ax.plot(*self._xy(np.zeros((1, 3))), color="0.15" if k % 2 == 0 else
                                  "0.55", lw=1.4, ls="-" if k % 2 == 0 else "--")[0]
                     for k in range(6)]
        self.feet = [self.ax.plot(*self._xy(np.zeros((1, 3))), "o", ms=6, mec="k", mew=0.6)[0]
                     for k in range(6)]
        self.arrows = []
        self.quiver = None
        if frames.force is not None and view != "3d":
            y0 = np.zeros(6)
            self.quiver = self.ax.quiver(y0, y0, y0, y0, angles="xy", scale_units="xy", scale=1,
                                         color=FORCE_COLOR, width=0.004, zorder=5)
        self.clock = self.fig.text(0.08, 0.955, "", fontsize=10, family="monospace")
        self.flag = self.fig.text(0.97, 0.955, "", fontsize=10, color=RELAXED_COLOR, ha="right")
        handles = [Line2D([], [], marker="o", ls="", color=c, mec="k", label=n)
                   for c, n in zip(PHASE_COLORS, PHASE_NAMES)]
        handles += [Line2D([], [], color="0.15", label="left legs"),
                    Line2D([], [], color="0.55", ls="--", label="right legs")]
        if frames.force is not None:
            handles.append(Line2D([], [], color=FORCE_COLOR,
                                  label=f"contact force ({self.scale * 100:.2g} m per 100 N)"))
        if view == "3d":
            self.fig.legend(handles=handles, fontsize=7, loc="upper right",
                            bbox_to_anchor=(0.99, 0.93))
        else:
            self.ax.legend(handles=handles, fontsize=7, loc="upper left", ncol=2)
        self.strip = self.fig.add_subplot(grid[1])
        self._timeline()
        self.fig.text(0.005, 0.005, os.path.basename(motion.source), fontsize=7, color="0.4")

    def _xy(self, pts):
        return self.p(np.asarray(pts))

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
            self.ax.plot(y, z, color="0.35", lw=1.0, label=f"terrain ({kind})", zorder=1)

    def _timeline(self):
        ax, m, f = self.strip, self.m, self.f
        t = m.time
        ax.set_xlim(f.times[0], max(t[-1], f.times[-1]))
        ax.set_ylim(-0.5, 6.8)
        ax.set_yticks(range(6), [f"L{6 - r}" for r in range(6)])
        ax.set_xlabel("time [s]", fontsize=8)
        ax.tick_params(labelsize=7)
        if m.has("/contacts/phase"):
            phase = np.asarray(m.data["/contacts/phase"])
            widths = np.diff(np.append(t, t[-1]))
            for leg in range(6):
                row = 5 - leg
                for code in (1, 2):
                    sel = phase[:, leg] == code
                    if sel.any():
                        ax.broken_barh(list(zip(t[sel], widths[sel])), (row - 0.4, 0.8),
                                       color=PHASE_COLORS[code], lw=0)
        if m.has("/solver/status"):
            status = np.asarray(m.data["/solver/status"])
            for code, color in ((1, RELAXED_COLOR), (2, FAILED_COLOR)):
                sel = status == code
                if sel.any():
                    ax.vlines(t[sel], 5.9, 6.7, color=color, lw=0.8)
            ax.text(1.0, 1.02, "red ticks: relaxed samples; black: failed", fontsize=7,
                    transform=ax.transAxes, ha="right", va="bottom")
        self.cursor = ax.axvline(f.times[0], color="k", lw=1.0)

    def update(self, i):
        f = self.f
        hips = np.stack([leg[i, 0] for leg in f.legs])
        order = self._hip_order(hips)
        ring = np.concatenate([hips[order], hips[order[:1]]])
        artists = []
        self._set(self.trunk, ring)
        for k in range(6):
            self._set(self.legs[k], f.legs[k][i])
            self._set(self.feet[k], f.feet[i, k][None])
            code = int(f.phase[i, k]) if f.phase is not None else 0
            self.feet[k].set_color(PHASE_COLORS[code])
            self.feet[k].set_markeredgecolor("k")
        artists += [self.trunk] + self.legs + self.feet
        if f.force is not None:
            vec = f.force[i] * self.scale
            if self.view == "3d":
                for a in self.arrows:
                    a.remove()
                start = f.feet[i]
                self.arrows = [self.ax.quiver(start[:, 0], start[:, 1], start[:, 2], vec[:, 0],
                                              vec[:, 1], vec[:, 2], color=FORCE_COLOR, lw=1.2,
                                              arrow_length_ratio=0.2)]
            else:
                self.quiver.set_offsets(np.stack([f.feet[i, :, 1], f.feet[i, :, 2]], axis=1))
                self.quiver.set_UVC(vec[:, 1], vec[:, 2])
                artists.append(self.quiver)
        self.clock.set_text(f"t = {f.times[i]:7.3f} s")
        flags = []
        if f.relaxed is not None and f.relaxed[i]:
            flags.append(f"{int(f.relaxed[i])} relaxed sample(s)")
        if f.failed is not None and f.failed[i]:
            flags.append(f"{int(f.failed[i])} failed sample(s)")
        self.flag.set_text(("since the last frame: " + ", ".join(flags)) if flags else "")
        self.cursor.set_xdata([f.times[i], f.times[i]])
        return artists + [self.clock, self.flag, self.cursor]

    def _set(self, line, pts):
        if self.view == "3d":
            line.set_data_3d(pts[:, 0], pts[:, 1], pts[:, 2])
        else:
            line.set_data(pts[:, 1], pts[:, 2])

    def _hip_order(self, hips):
        """The hips around their centre, in the trunk plane (the order of frame 0)."""
        if not hasattr(self, "_order"):
            c = hips.mean(axis=0)
            angle = np.arctan2(hips[:, 1] - c[1], hips[:, 0] - c[0])
            self._order = np.argsort(angle)
        return self._order


def render(motion, frames, out, view="side", dpi=80):
    """Writes the animation to `out` (format by extension) via a temporary file."""
    ext = os.path.splitext(out)[1].lower()
    directory = os.path.dirname(os.path.abspath(out))
    tmp = os.path.join(directory, f".{os.path.basename(out)}.tmp{os.getpid()}{ext}")
    scene = Scene(motion, frames, view, dpi)
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


def main(argv=None):
    ap = argparse.ArgumentParser(
        prog="animate.py", description=__doc__.strip().splitlines()[0],
        epilog="\n".join(__doc__.strip().splitlines()[4:]),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("result", help="a hexdyn result file, or a sweep file with --keep-runs runs")
    ap.add_argument("-o", "--output", required=True, help="OUT.gif, OUT.mp4 or OUT.html")
    ap.add_argument("--run", help="id of the kept run of a sweep file (/runs/ID)")
    ap.add_argument("--fps", type=float, default=25.0, help="frames per second (default 25)")
    ap.add_argument("--view", choices=("side", "3d"), default="side",
                    help="side: the y-z plane (default); 3d: a perspective")
    ap.add_argument("--dpi", type=int, default=80, help="pixels per inch of the 8 x 5.6 in "
                    "figure (default 80: 640 x 448 pixels)")
    args = ap.parse_args(argv)
    try:
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
        motion = load_motion(args.result, args.run)
        frames = frames_of(motion, args.fps)
    except InputError as e:
        print(f"animate: {e}", file=sys.stderr)
        return 2
    if motion.terrain is None:
        print(f"animate: warning: {motion.source} has no /terrain (a hexdyn-result/1 file): "
              "no terrain drawn", file=sys.stderr)
    err = motion.fk_error()
    if err > 1e-6:
        print(f"animate: warning: {motion.source}: the feet by forward kinematics of "
              f"/model/urdf differ from /feet/position by up to {err:.3g} m", file=sys.stderr)
    render(motion, frames, args.output, args.view, args.dpi)
    print(f"animate: wrote {args.output} ({len(frames)} frames at {args.fps:g} per second)",
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
