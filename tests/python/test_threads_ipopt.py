"""hexdyn.run from 2 threads with the Ipopt back end (allocation.solver: ipopt), whose
sequential MUMPS is not documented as thread-safe and which the module therefore runs one
scene at a time (bindings/python/module.cpp): 2 coarse paper scenes computed by 2 threads
give the bytes they give one after another, and both threads finish.
    test_threads_ipopt.py HEXDYN_BINARY SOURCE_DIR"""

import os
from concurrent.futures import ThreadPoolExecutor

import hexdyn
from common import args

_, SRC = args()
PAPER = os.path.join(SRC, "configs/paper.yaml")
# The grid as built (no refinement) and no required friction: the threads are the point here.
COARSE = {"allocation.solver": "ipopt", "output.sample_step": 0.5, "output.impact_samples": 2,
          "output.event_step": 0.1, "output.tolerance": 0, "output.required_friction": False}


def one(duty):
    r = hexdyn.run(PAPER, set=dict(COARSE, **{"gait.duty_factor": duty}))
    return {k: (v if isinstance(v, str) else v.tobytes() if v.dtype.kind != "O" else list(v))
            for k, v in r.items() if k != "/solver/seconds"}


serial = [one(x) for x in (0.75, 0.8)]
with ThreadPoolExecutor(2) as pool:
    parallel = list(pool.map(one, (0.75, 0.8)))
for a, b in zip(serial, parallel):
    diff = [k for k in a if a[k] != b[k]]
    assert not diff, f"Ipopt scenes from 2 threads differ from 1 in {diff}"
print("python threads with Ipopt: ok")
