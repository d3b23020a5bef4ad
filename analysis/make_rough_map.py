#!/usr/bin/python3
"""A rough height map for the terrain examples (configs/terrain/rough_map.yaml,
docs/validation/terrain.md#a-rough-height-map), written as a .npy file of float64 heights:
rows along y, columns along x, node (i, j) at (X0 + j RES, Y0 + i RES).

The ground is smooth noise (white noise, seeded, smoothed by a Gaussian of CORR m standard
deviation along both axes, scaled to AMPLITUDE m standard deviation) that rises along +y at
SLOPE (a gentle ramp), with flat raised slabs of SLAB_HEIGHT m: their sides are edges a foot
must keep its margin from. The same seed gives the same file, bit for bit.

    /usr/bin/python3 analysis/make_rough_map.py OUT.npy [--seed 46]

Prints the grid's shape, origin and resolution (the keys terrain.height_map.origin and
resolution of the scene that reads it).
"""

import argparse
import os
import sys

import numpy as np

X0, Y0, RES = -0.8, -1.0, 0.01          # m: the grid's first node and spacing
NX, NY = 161, 451                        # nodes: 1.6 m across, 4.5 m along
CORR, AMPLITUDE, SLOPE = 0.08, 0.006, 0.03   # m, m, rise per metre along +y
SLAB_HEIGHT = 0.03                       # m
# Slabs: (x0, x1, y0, y1) in m.
SLABS = [(-0.5, -0.1, 0.9, 1.3), (0.15, 0.55, 1.6, 2.1), (-0.35, 0.2, 2.5, 2.8)]


def smooth_noise(rng, ny, nx, sigma_nodes):
    """White noise convolved with a normalised Gaussian along both axes (reflected borders),
    scaled to unit standard deviation."""
    w = np.arange(-int(4 * sigma_nodes), int(4 * sigma_nodes) + 1)
    g = np.exp(-0.5 * (w / sigma_nodes) ** 2)
    g /= g.sum()
    pad = len(w) // 2
    n = rng.standard_normal((ny + 2 * pad, nx + 2 * pad))
    n = np.apply_along_axis(lambda r: np.convolve(r, g, mode="same"), 1, n)
    n = np.apply_along_axis(lambda c: np.convolve(c, g, mode="same"), 0, n)
    n = n[pad:pad + ny, pad:pad + nx]
    return (n - n.mean()) / n.std()


def rough_map(seed):
    rng = np.random.default_rng(seed)
    x = X0 + RES * np.arange(NX)
    y = Y0 + RES * np.arange(NY)
    z = AMPLITUDE * smooth_noise(rng, NY, NX, CORR / RES) + SLOPE * np.maximum(y, 0.0)[:, None]
    for xa, xb, ya, yb in SLABS:
        inside = ((x[None, :] >= xa) & (x[None, :] <= xb) & (y[:, None] >= ya) & (y[:, None] <= yb))
        base = z[inside].max()
        z[inside] = base + SLAB_HEIGHT
    return z


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("--seed", type=int, default=46)
    a = ap.parse_args()
    z = rough_map(a.seed)
    tmp = f"{a.out}.tmp.{os.getpid()}.npy"
    try:
        np.save(tmp, z)
        os.replace(tmp, a.out)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    print(f"{a.out}: {z.shape[0]} rows (y) x {z.shape[1]} columns (x), origin [{X0}, {Y0}] m, "
          f"resolution {RES} m, heights {z.min():.4f} to {z.max():.4f} m")
    return 0


if __name__ == "__main__":
    sys.exit(main())
