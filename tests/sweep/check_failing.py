#!/usr/bin/python3
"""Checks the rows of tests/sweep/failing.yaml's sweep file (argument), read with the
analysis reader: riser 0.04 with duty 1/2 and 3/4 computed; riser 0.12 out of reach;
duty 1.2 out of range, each with its message, metrics NaN where not computed."""
import math
import sys

import numpy as np  # noqa: E402

from hexdyn import results as hr  # noqa: E402

sw = hr.open_sweep(sys.argv[1])
assert sw.shape == (2, 3), sw.shape
expected = ["ok", "ok", "config", "reach", "reach", "config"]
assert sw.status_names == expected, sw.status_names
msg = sw.table["message"]
for i, status in enumerate(expected):
    energy = float(sw.table["energy"][i])
    if status == "ok":
        assert msg[i] == "", msg[i]
        assert math.isfinite(energy) and energy > 0, energy
        assert np.all(np.isfinite(sw.table["peak_torque"][i]))
    else:
        assert math.isnan(energy), energy
        assert np.all(np.isnan(sw.table["peak_torque"][i]))
    if status == "config":
        assert msg[i] == (f"scenario {sw.table['id'][i]}: gait.duty_factor: got 1.2, "
                          "expected a number in [0.5, 1)"), msg[i]
    if status == "reach":
        assert msg[i].startswith("leg L") and "not reachable" in msg[i], msg[i]
print("check_failing: ok:", ", ".join(f"{i} {s}" for i, s in zip(sw.table["id"], expected)))
