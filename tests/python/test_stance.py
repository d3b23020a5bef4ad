"""A URDF robot's stance fallback in Python (model/stance.hpp): hexdyn.validate and hexdyn.run
issue the warnings `hexdyn validate` prints on stderr as UserWarning, validate's dict lists
them, and the Result's resolved configuration records how each leg stands; robot.nominal_pose
for the leg removes the warning.
    test_stance.py HEXDYN_BINARY SOURCE_DIR      (PYTHONPATH: the build tree's python/)"""

import os
import re
import subprocess
import tempfile
import warnings

import hexdyn
from common import args

HEXDYN, SRC = args()
SCENE = """robot: {urdf: robot.urdf}
terrain: {type: flat}
gait: {duty_factor: 0.5, stroke: 0.0625, swing_clearance: 0.01, touchdown_speed: 0.05}
motion: {peak_speed: 0.05, cycles: 2, ramp_duration: 1, posture: {height: auto, start_y: 0}}
contact: {model: compliant, stiffness: 3.98e11, exponent: 2.2, damping_max: 1.0e4,
          full_damping_depth: 1.0e-5, friction_coefficient: 0.6}
allocation: {friction: pyramid4}
output: {sample_step: 0.5, grid: uniform}
"""
FALLBACK = "fallback: mid-range joint angles (joint left_middle_tibia outside its limits)"


def caught(call):
    """(the call's value, the messages of the UserWarnings it issued)."""
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        value = call()
    return value, [str(x.message) for x in w if issubclass(x.category, UserWarning)]


with tempfile.TemporaryDirectory() as d:
    # The PhantomX with its L3 tibia limited to [1.1, 2.18] rad: the default pose's 1.057 rad
    # is out of reach, and the robot still walks on flat ground.
    with open(os.path.join(SRC, "robots/phantomx_mark4.urdf")) as f:
        urdf = f.read()
    at = urdf.index('<joint name="left_middle_tibia"')
    end = urdf.index("/>", urdf.index("<limit", at))
    urdf = urdf[:at] + re.sub(r'lower="[^"]*"', 'lower="1.1"', urdf[at:end], count=1) + urdf[end:]
    with open(f"{d}/robot.urdf", "w") as f:
        f.write(urdf)
    scene = f"{d}/scene.yaml"
    with open(scene, "w") as f:
        f.write(SCENE)

    cli = subprocess.run([HEXDYN, "validate", scene], capture_output=True, text=True, check=True)
    want = [line[len("hexdyn: warning: "):] for line in cli.stderr.splitlines()]
    assert len(want) == 1 and want[0].startswith("L3: the nominal pose is out of reach"), cli.stderr
    report, issued = caught(lambda: hexdyn.validate(scene))
    assert report["warnings"] == want, (report["warnings"], want)
    assert issued == ["hexdyn: " + w for w in want], issued

    result, issued = caught(lambda: hexdyn.run(scene))
    assert issued == ["hexdyn: " + w for w in want], issued
    record = result.config["auto"]["robot"]["nominal_pose"]
    assert record["L3"]["source"] == FALLBACK, record["L3"]
    assert all(record[f"L{i}"]["source"] == "nominal pose" for i in (1, 2, 4, 5, 6)), record

    fixed, issued = caught(lambda: hexdyn.run(scene, set={"robot.nominal_pose": "{L3: [0, 0, 1.5]}"}))
    assert issued == [], issued
    assert fixed.config["auto"]["robot"]["nominal_pose"]["L3"]["source"] == "robot.nominal_pose"
    assert hexdyn.validate(scene, set={"gait.foot_lateral": 0.1})["warnings"] == []
print("stance in Python: warnings, record and fix checked")
