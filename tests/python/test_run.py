"""hexdyn.run against `hexdyn run`: for the paper scene with an override and for a URDF robot
(whose file has /model/leg_mapping), every dataset of the file `hexdyn run` writes is in the
Result, bit for bit (dtype, shape, bytes; text equal; /solver/seconds, the clock's, in shape and dtype only),
and nothing else is; the /meta
attributes agree (but the clock's: created_utc, wall_time_s); r.config is the resolved
configuration; r.write writes a file with the same datasets; version and commit are those of
`hexdyn --version`.
    test_run.py HEXDYN_BINARY SOURCE_DIR      (PYTHONPATH: the build tree's python/)"""

import os
import subprocess
import tempfile

import numpy as np
import yaml

import hexdyn
from common import args, cli_run, file_datasets, same_dataset

HEXDYN, SRC = args()
TIMING = "/solver/seconds"
CASES = [
    ("configs/paper.yaml", {"gait.duty_factor": "3/4"}, ["gait.duty_factor=3/4"]),
    ("configs/robots/kraby_stairs.yaml", {}, []),
]

version = subprocess.run([HEXDYN, "--version"], capture_output=True, text=True, check=True).stdout.split()
assert version[1] == hexdyn.__version__, (version, hexdyn.__version__)
assert version[2] == f"({hexdyn.__git_commit__})", (version, hexdyn.__git_commit__)

with tempfile.TemporaryDirectory() as d:
    for scene, sets, cli_sets in CASES:
        path = os.path.join(SRC, scene)
        rc, err = cli_run(HEXDYN, path, f"{d}/cli.h5", cli_sets)
        assert rc == 0, err
        want, want_attrs = file_datasets(f"{d}/cli.h5")
        r = hexdyn.run(path, set=sets)
        assert set(r) == set(want), f"{scene}: only in the file {set(want) - set(r)}, only in the Result {set(r) - set(want)}"
        # /solver/seconds is the clock's (time per allocation solve): its shape and dtype only.
        problems = [p for k in want if (p := same_dataset(k, want[k][0], want[k][1], r[k]))
                    and not (k == TIMING and r[k].shape == want[k][0].shape and r[k].dtype == want[k][1])]
        assert not problems, f"{scene}: " + "; ".join(problems)
        for k, v in want_attrs.items():
            if k not in ("created_utc", "wall_time_s"):
                assert r.attrs[k] == v, f"{scene}: /meta {k}: {r.attrs[k]!r} != {v!r}"
        assert set(r.attrs) == set(want_attrs), (set(r.attrs), set(want_attrs))
        assert r.config == yaml.safe_load(want_attrs["config_yaml"])
        if sets:
            assert r.config["gait"]["duty_factor"] == 0.75, r.config["gait"]
        r.write(f"{d}/py.h5")
        again, _ = file_datasets(f"{d}/py.h5")
        assert set(again) == set(want)
        for k in want:
            assert want[k][2] == again[k][2], f"{k}: units"
            if k != TIMING:
                assert same_dataset(k, again[k][0], again[k][1], r[k]) is None, f"written {k} differs"
        print(f"{scene}: {len(want)} datasets bit for bit, energy {float(r['/energy/total']):.6g} J")

    # Typed override values mean what --set means: a number, a list, a string.
    a = hexdyn.run(os.path.join(SRC, "configs/paper.yaml"), set={"gait.duty_factor": 0.75})
    b = hexdyn.run(os.path.join(SRC, "configs/paper.yaml"), set={"gait.duty_factor": "3/4"})
    assert a["/energy/total"].tobytes() == b["/energy/total"].tobytes()
    assert np.array_equal(a["/joints/torque"], b["/joints/torque"])
print("python run: ok")
