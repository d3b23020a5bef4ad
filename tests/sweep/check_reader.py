#!/usr/bin/python3
"""Reads the smoke sweep file (argument) with hexdyn.open_sweep (bindings/python/hexdyn/results.py) and
checks it against the sweep file and against its own kept runs: axes and grid order,
table shapes and units, and per-scenario metrics recomputed from /runs/<id>."""
import sys

import numpy as np  # noqa: E402

from hexdyn import results as hr  # noqa: E402

sw = hr.open_sweep(sys.argv[1])
assert sw.meta["schema"] == hr.SWEEP_SCHEMA and sw.meta["schema_version"] == hr.SWEEP_SCHEMA_VERSION
for key in hr.SWEEP_META_ATTRIBUTES:
    assert key in sw.meta, key
spec = sw.spec
assert [a.key for a in sw.axes] == [a["key"] for a in spec["axes"]]
assert sw.shape == tuple(len(a["values"]) for a in spec["axes"]) == (2, 2, 2)
assert sw.axes[2].labels == ["1/2", "3/4"] and list(sw.axes[2].values) == [0.5, 0.75]
assert sw.config["motion"]["cycles"] == 1 and sw.config["output"]["grid"] == "uniform"
n = sw.size
for name, (shape, units, _) in hr.SCENARIO_DATASETS.items():
    col = sw.table[name]
    dims = {"N": n, "A": len(sw.axes), "J": len(hr.joint_names(sw))}
    want = tuple(dims.get(d, d) for d in shape)
    got = (len(col),) if isinstance(col, list) else np.shape(col)
    assert got == want, (name, got, want)
    assert sw.units[name] == units, (name, sw.units[name], units)
assert sw.ok.all(), sw.status_names
# Row-major grid: scenario i = ((a * 2) + b) * 2 + c.
for i in range(n):
    a, b, c = np.unravel_index(i, sw.shape)
    assert sw.scenario(i) == {sw.axes[0].key: sw.axes[0].values[a],
                              sw.axes[1].key: sw.axes[1].values[b],
                              sw.axes[2].key: sw.axes[2].values[c]}
    assert list(sw.table["axis_index"][i]) == [a, b, c]
assert np.array_equal(sw.grid("energy")[1, 0, 1], sw.table["energy"][5])
# Metrics against the full results of the runs.
for i in range(n):
    run = sw.run(i)
    cfg = run.config
    for key, value in sw.scenario(i).items():
        section, leaf = key.split(".")
        assert cfg[section][leaf] == value, (key, cfg[section][leaf], value)
    tau = np.asarray(run["/joints/torque"])
    t = np.asarray(run["/time"])
    assert np.array_equal(sw.table["peak_torque"][i], np.abs(tau).max(axis=0))
    rms = np.sqrt(np.trapz(tau ** 2, t, axis=0) / (t[-1] - t[0]))
    assert np.allclose(sw.table["rms_torque"][i], rms, rtol=1e-12, atol=0)
    assert sw.table["energy"][i] == run["/energy/total"]
    assert sw.table["cost_of_transport"][i] == run["/energy/cost_of_transport"]
    assert sw.table["peak_impact_force"][i] == np.max(run["/impacts/peak_force"])
    assert sw.table["relaxed_samples"][i] == int(np.sum(run["/solver/status"] == 1))
    assert sw.table["samples"][i] == len(t)
print(f"check_reader: ok: {sw}")
