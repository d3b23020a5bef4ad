"""The drive train (docs/theory/drive-train.md, docs/user/configuration.md#actuators) through
`hexdyn run`, checked against a second computation in numpy (tests/python/drive_check.py):

  a. A paper scene whose actuators differ per joint type and per joint name (the MX-64 and
     MX-106 of the servo table, a femur with gear efficiency 0.8 and a rotor inertia, a
     joint with regeneration 0.5 and its own resistance, a joint with no bound, a supply
     low enough that a joint outruns its no-load speed, a thermal window shorter than the
     run): every drive-train dataset recomputed from /joints/torque, velocity,
     acceleration and /meta actuators.joints to 1e-9 (drive_check.py states the rule),
     the windowed RMS maximum by an exact method of this file's own; each branch of the
     formulas is taken on some sample (counted), and the resolved values of the servo
     table's joints are those of docs/user/servos.md to its four significant figures.
  b. Resolution: with explicit values, /meta actuators.joints.NAME holds, key by key, the
     value of the most specific entry (joints.NAME > type > default), armature = G² J_m
     with the joint's own G, the documented defaults, and no optional key not given.
  c. allocation.objective copper_loss: with identical actuators (no friction, no armature)
     the same /contacts/force and /joints/torque as torque_squared, bit for bit; with
     resistances that differ per joint type, a copper loss no larger than
     torque_squared's, sample by sample and over the run, and smaller somewhere.
  d. A URDF robot (robots/phantomx_mark4.urdf) with <dynamics damping friction> added to
     some joints: with an actuators section that gives no friction, those are each
     joint's viscous and Coulomb friction; an entry's own value overrides them; the
     drive-train datasets recompute (torque limit: the URDF's effort where no bound).
     Without an actuators section the same URDF gives no drive datasets and the results
     of the unmodified URDF, bit for bit.
  e. Bad actuators input: exit status 2, one line on stderr naming the key path; no output
     file written, an existing one left as it was.

    test_drive_train.py HEXDYN_BINARY SOURCE_DIR      (PYTHONPATH: the build tree's python/)
"""

import os
import re
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

import numpy as np
import yaml

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import args, cli_run  # noqa: E402
import drive_check  # noqa: E402

HEXDYN, SRC = args()
PAPER = os.path.join(SRC, "configs", "paper.yaml")
PHANTOMX = os.path.join(SRC, "configs", "robots", "phantomx_mark4_stairs.yaml")
PHANTOMX_URDF = os.path.join(SRC, "robots", "phantomx_mark4.urdf")
TYPES = ("coxa", "femur", "tibia")  # joint k of a leg is TYPES[k % 3] (docs/user/output.md)


def scene(d, name, body, base=PAPER):
    """A scene file `name` in d inheriting `base`, with the keys of `body` (a dict)."""
    path = os.path.join(d, name)
    with open(path, "w") as f:
        yaml.safe_dump(dict({"inherit": base}, **body), f, sort_keys=False)
    return path


def run(d, path, sets=()):
    """`hexdyn run path --set ...` into d; the file's path (the run must succeed)."""
    out = os.path.join(d, os.path.basename(path).replace(".yaml", ".h5"))
    rc, err = cli_run(HEXDYN, path, out, sets)
    assert rc == 0, f"{path} {list(sets)}: exit {rc}: {err}"
    return out


def assert_branches(counts, needed, label):
    print(f"{label}: " + ", ".join(f"{k} {v}" for k, v in counts.items()))
    empty = [k for k in needed if counts[k] == 0]
    assert not empty, f"{label}: no sample takes the branch(es) {empty}: the check would be vacuous"


# ---- a. every dataset against a second computation ----------------------------------------

MIXED = {"actuators": {
    # Default: explicit values without a voltage or peak rating (the tibias other than L2 and
    # L3 keep allocation.torque_limit); the coxas and femurs the MX-64 of the table.
    "default": {"gear_ratio": 200, "torque_constant": 0.0081, "resistance": 3.95,
                "coulomb_friction": 0.05, "viscous_friction": 0.02, "armature": 0.004},
    "coxa": {"model": "dynamixel_mx64"},
    "femur": {"model": "dynamixel_mx64", "gear_efficiency": 0.8, "rotor_inertia": 3.0e-7,
              "continuous_torque": 2.0, "thermal_window": 1.0},
    "joints": {
        "L2_tibia": {"model": "dynamixel_mx106", "regeneration": 0.5, "resistance": 2.0,
                     "continuous_torque": 3.0, "thermal_window": 0.5},
        "L5_coxa": {"voltage": 1.0},  # no-load speed 0.62 rad/s: the bound falls to 0
        "L3_tibia": {"voltage": 12.0, "peak_torque": 5.0},
    }}}


def servo_table():
    """The servo table of docs/user/servos.md: {model: {key: value}}, four significant
    figures (joint side; k_t in mN m/A)."""
    with open(os.path.join(SRC, "docs/user/servos.md")) as f:
        rows = [line for line in f if line.startswith("| `dynamixel_")]
    keys = ("gear_ratio", "torque_constant", None, "resistance", "armature", "coulomb_friction",
            "viscous_friction", "gear_efficiency", "voltage", "peak_torque", "continuous_torque")
    table = {}
    for line in rows:
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) != 12:
            continue
        values = dict(zip(keys, (float(c) for c in cells[1:])))
        values.pop(None)
        values["torque_constant"] *= 1e-3
        table[cells[0].strip("`")] = values
    assert {"dynamixel_mx64", "dynamixel_mx106"} <= set(table), sorted(table)
    return table


def check_servo_values(r):
    """Joints whose values all come from a servo of the table have its values (four
    significant figures, as docs/user/servos.md prints them; NaN there: the default)."""
    table = servo_table()
    joints = r["config"]["actuators"]["joints"]
    defaults = {"armature": 0.0, "coulomb_friction": 0.0, "viscous_friction": 0.0,
                "gear_efficiency": 1.0}
    for name in ("L1_coxa", "L4_coxa"):  # coxa: dynamixel_mx64 only
        got = joints[name]
        assert got.get("model") == "dynamixel_mx64", (name, got)
        for k, v in table["dynamixel_mx64"].items():
            if np.isnan(v):
                assert k not in got or got[k] == defaults[k], (name, k, got)
            else:
                assert abs(got[k] - v) <= 5e-4 * abs(v), f"{name}.{k}: {got[k]}, the servo table {v}"
    # L2_tibia: the MX-106 over the default entry, with its own resistance.
    got = joints["L2_tibia"]
    assert got["model"] == "dynamixel_mx106" and got["resistance"] == 2.0, got
    for k in ("gear_ratio", "torque_constant", "armature", "voltage", "peak_torque"):
        v = table["dynamixel_mx106"][k]
        assert abs(got[k] - v) <= 5e-4 * abs(v), f"L2_tibia.{k}: {got[k]}, the servo table {v}"


def part_a(d):
    path = run(d, scene(d, "mixed.yaml", MIXED))
    r = drive_check.read_file(path)
    counts = drive_check.check(r, "mixed actuators")
    assert_branches(counts, [
        "driving (τ_drive q̇ > 0)", "back-driven (τ_drive q̇ < 0)", "back-driven with η < 1",
        "at rest (q̇ = 0)", "P < 0, regenerated (r > 0)", "P < 0, lost (r = 0)",
        "bound: voltage", "bound: voltage clipped at 0", "bound: peak",
        "bound: allocation.torque_limit", "windowed RMS shorter than the run",
        "windowed maximum inside a piece"], "a")
    p = drive_check.parameters(r)
    # The windowed RMS of a window shorter than the run exceeds the run's RMS somewhere.
    short = p["thermal_window"] < r["/time"][-1] - r["/time"][0]
    assert np.any(r["/joints/drive_torque_window_rms"][short]
                  > r["/joints/drive_torque_rms"][short] * (1 + 1e-6))
    # The drive torque differs from the link torque by more than the tolerance.
    assert np.max(np.abs(r["/joints/drive_torque"] - r["/joints/torque"])) > 1e-3
    check_servo_values(r)
    print("a. every drive-train dataset recomputed to 1e-9")


# ---- b. resolution of the entries -----------------------------------------------------------

EXPLICIT = {"actuators": {
    "default": {"gear_ratio": 100, "torque_constant": 0.01, "resistance": 4.0,
                "coulomb_friction": 0.1, "voltage": 24.0, "regeneration": 0.25},
    "coxa": {"resistance": 5.0, "peak_torque": 5.5},
    "femur": {"gear_ratio": 150, "rotor_inertia": 2.0e-6, "viscous_friction": 0.03,
              "gear_efficiency": 0.9},
    "tibia": {"armature": 0.004, "continuous_torque": 1.0, "thermal_window": 2.0},
    "joints": {
        "L3_femur": {"torque_constant": 0.02, "armature": 0.05},
        "L4_femur": {"gear_ratio": 120},
        "L1_tibia": {"gear_ratio": 300, "peak_torque": 4.5, "coulomb_friction": 0.0},
        "L6_coxa": {"rotor_inertia": 1.0e-7, "voltage": 12.0, "regeneration": 1.0},
    }}}


def expected_resolution(section, name, k):
    """The resolved values of joint `name` (index k) by the rule of
    docs/user/configuration.md#actuators, written independently of hexdyn."""
    merged, inertia = {}, ("armature", 0.0)
    for entry in (section.get("default", {}), section.get(TYPES[k % 3], {}),
                  section.get("joints", {}).get(name, {})):
        for key, v in entry.items():
            if key in ("rotor_inertia", "armature"):
                inertia = (key, float(v))
            else:
                merged[key] = float(v)
    want = {"coulomb_friction": 0.0, "viscous_friction": 0.0, "gear_efficiency": 1.0,
            "regeneration": 0.0}
    want.update(merged)
    G = want["gear_ratio"]
    want["armature"] = G * G * inertia[1] if inertia[0] == "rotor_inertia" else inertia[1]
    return want


def part_b(d):
    path = run(d, scene(d, "explicit.yaml", EXPLICIT))
    r = drive_check.read_file(path)
    resolved = r["config"]["actuators"]["joints"]
    assert sorted(resolved) == sorted(r["joints"]), sorted(resolved)
    for k, name in enumerate(r["joints"]):
        want = expected_resolution(EXPLICIT["actuators"], name, k)
        got = resolved[name]
        assert set(got) == set(want), f"{name}: keys {sorted(got)}, expected {sorted(want)}"
        for key in want:
            assert float(got[key]) == want[key], f"{name}.{key}: {got[key]!r}, expected {want[key]!r}"
    # The cases the scene was written for, spelt out.
    assert resolved["L3_femur"]["armature"] == 0.05            # joint's armature over femur's J_m
    assert resolved["L4_femur"]["armature"] == 120.0 * 120.0 * 2.0e-6  # femur's J_m, joint's G
    assert resolved["L2_femur"]["armature"] == 150.0 * 150.0 * 2.0e-6
    assert resolved["L6_coxa"]["armature"] == 100.0 * 100.0 * 1.0e-7
    assert resolved["L1_tibia"]["coulomb_friction"] == 0.0 and resolved["L2_tibia"]["coulomb_friction"] == 0.1
    assert "peak_torque" not in resolved["L1_femur"] and "continuous_torque" not in resolved["L1_coxa"]
    assert "model" not in resolved["L1_coxa"]
    drive_check.check(r, "explicit actuators")
    print("b. /meta actuators.joints: most specific entry, key by key")


# ---- c. allocation.objective copper_loss ----------------------------------------------------

def part_c(d):
    identical = {"actuators": {"default": {"model": "dynamixel_mx64", "coulomb_friction": 0.0,
                                           "viscous_friction": 0.0, "armature": 0.0}}}
    files = {}
    for objective in ("torque_squared", "copper_loss"):
        body = dict(identical, allocation={"objective": objective})
        files[objective] = drive_check.read_file(run(d, scene(d, f"same_{objective}.yaml", body)))
    a, b = files["torque_squared"], files["copper_loss"]
    assert b["config"]["allocation"]["objective"] == "copper_loss"
    assert np.array_equal(a["/time"], b["/time"])
    for name in ("/contacts/force", "/joints/torque"):
        assert np.array_equal(a[name], b[name]), f"identical actuators: {name} differs"

    # Resistances per joint type; η = 1 and no friction, armature or drive bound, so that
    # copper_loss minimises each sample's copper loss over the same constraints as
    # torque_squared; output.tolerance 0: both runs on the grid as built.
    resistances = {"default": {"gear_ratio": 200, "torque_constant": 0.0081, "resistance": 3.95},
                   "coxa": {"resistance": 0.5}, "tibia": {"resistance": 20.0}}
    for objective in ("torque_squared", "copper_loss"):
        body = {"actuators": resistances, "allocation": {"objective": objective},
                "output": {"tolerance": 0}}
        files[objective] = drive_check.read_file(run(d, scene(d, f"ohm_{objective}.yaml", body)))
    a, b = files["torque_squared"], files["copper_loss"]
    assert np.array_equal(a["/time"], b["/time"])
    drive_check.check(a, "torque_squared, resistances per type")
    drive_check.check(b, "copper_loss, resistances per type")
    loss = {}
    for key, r in files.items():
        R = drive_check.parameters(r)["resistance"]
        loss[key] = np.sum(R * r["/joints/current"] ** 2, axis=1)
    both = (a["/solver/status"] == 0) & (b["/solver/status"] == 0)
    assert np.sum(both) > 250, f"{np.sum(both)} samples optimal in both runs"
    assert np.all(loss["copper_loss"][both] <= loss["torque_squared"][both] * (1 + 1e-6) + 1e-9), \
        "copper_loss: a sample with more copper loss than torque_squared's"
    ea, eb = float(a["/energy/copper_loss"]), float(b["/energy/copper_loss"])
    assert eb <= ea, f"copper_loss {eb} J > torque_squared {ea} J"
    assert eb < ea * (1 - 1e-3), f"copper_loss {eb} J, torque_squared {ea} J: no difference to test"
    assert not np.array_equal(a["/contacts/force"], b["/contacts/force"])
    print(f"c. copper_loss = torque_squared with identical actuators; copper loss {eb:.4g} J "
          f"against {ea:.4g} J with resistances per joint type")


# ---- d. a URDF robot's <dynamics> ----------------------------------------------------------

def urdf_with_dynamics(d, dynamics):
    """robots/phantomx_mark4.urdf with <dynamics> set on the joints of `dynamics`
    ({joint: {attribute: value}}), written to d."""
    tree = ET.parse(PHANTOMX_URDF)
    found = set()
    for joint in tree.getroot().findall("joint"):
        name = joint.get("name")
        if name in dynamics:
            for old in joint.findall("dynamics"):
                joint.remove(old)
            ET.SubElement(joint, "dynamics", {k: repr(v) for k, v in dynamics[name].items()})
            found.add(name)
    assert found == set(dynamics), set(dynamics) - found
    path = os.path.join(d, "phantomx_dynamics.urdf")
    tree.write(path)
    return path


def part_d(d):
    dynamics = {"right_front_coxa": {"damping": 0.021, "friction": 0.037},
                "right_front_femur": {"damping": 0.013, "friction": 0.052},
                "left_middle_tibia": {"damping": 0.04},
                "left_back_femur": {"friction": 0.06},
                "right_back_tibia": {"damping": 0.011, "friction": 0.019}}
    urdf = urdf_with_dynamics(d, dynamics)
    short = ["robot.urdf=" + urdf, "motion.cycles=2"]
    actuators = {"default": {"gear_ratio": 200, "torque_constant": 0.0081, "resistance": 3.95,
                             "armature": 0.002},
                 "tibia": {"viscous_friction": 0.07},
                 "joints": {"right_front_femur": {"coulomb_friction": 0.11}}}
    r = drive_check.read_file(run(d, scene(d, "px_drive.yaml", {"actuators": actuators},
                                           base=PHANTOMX), short))
    resolved = r["config"]["actuators"]["joints"]
    # The URDF's own <dynamics> (robots/phantomx_mark4.urdf gives friction 0.5 to every
    # joint), as written to the file run.
    urdf_dynamics = {j.get("name"): {k: float(v) for k, v in j.find("dynamics").attrib.items()}
                     for j in ET.parse(urdf).getroot().findall("joint")
                     if j.find("dynamics") is not None}
    for k, name in enumerate(r["joints"]):
        urdf_values = urdf_dynamics.get(name, {})
        want_b = 0.07 if TYPES[k % 3] == "tibia" else urdf_values.get("damping", 0.0)
        want_c = 0.11 if name == "right_front_femur" else urdf_values.get("friction", 0.0)
        assert resolved[name]["viscous_friction"] == want_b, (name, resolved[name], want_b)
        assert resolved[name]["coulomb_friction"] == want_c, (name, resolved[name], want_c)
    assert resolved["right_front_coxa"]["viscous_friction"] == 0.021
    assert resolved["right_back_tibia"]["coulomb_friction"] == 0.019
    assert resolved["left_middle_tibia"]["coulomb_friction"] == 0.0   # damping only
    assert resolved["right_middle_coxa"]["coulomb_friction"] == 0.5   # the URDF as shipped
    assert resolved["left_back_femur"]["viscous_friction"] == 0.0
    assert r["config"]["allocation"]["torque_limit"] == "effort"
    counts = drive_check.check(r, "URDF robot")
    assert counts["bound: allocation.torque_limit"] > 0

    plain = drive_check.read_file(run(d, scene(d, "px_plain.yaml", {}, base=PHANTOMX), short))
    original = drive_check.read_file(run(d, scene(d, "px_original.yaml", {}, base=PHANTOMX),
                                         ["motion.cycles=2"]))
    assert "actuators" not in plain["config"], plain["config"].get("actuators")
    present = [k for k in drive_check.DRIVE_DATASETS if k in plain]
    assert not present, f"URDF <dynamics> without actuators: {present} written"
    for name in ("/time", "/joints/torque", "/contacts/force", "/joints/velocity"):
        assert np.array_equal(plain[name], original[name]), \
            f"without actuators, the URDF's <dynamics> changed {name}"
    print("d. URDF <dynamics>: the friction defaults below every entry; none without actuators")


# ---- e. bad input ---------------------------------------------------------------------------

BAD = [
    ("unknown model", {"actuators": {"default": {"model": "dynamixel_nope"}}},
     "actuators.default.model", "dynamixel_mx64"),
    ("missing gear_ratio", {"actuators": {"default": {"torque_constant": 0.01, "resistance": 4}}},
     "actuators.joints.L1_coxa.gear_ratio", "missing"),
    ("gear_efficiency 0", {"actuators": {"default": {"model": "dynamixel_mx64",
                                                     "gear_efficiency": 0}}},
     "actuators.default.gear_efficiency", "got 0"),
    ("both rotor_inertia and armature",
     {"actuators": {"default": {"model": "dynamixel_mx64"},
                    "femur": {"rotor_inertia": 1e-7, "armature": 0.01}}},
     "actuators.femur", "rotor_inertia and armature"),
    ("unknown joint name", {"actuators": {"default": {"model": "dynamixel_mx64"},
                                          "joints": {"L7_femur": {"resistance": 3}}}},
     "actuators.joints.L7_femur", "L1_coxa"),
    ("unknown key in an entry", {"actuators": {"default": {"model": "dynamixel_mx64",
                                                           "gear_ration": 200}}},
     "actuators.default.gear_ration", "unknown key"),
    ("unknown entry", {"actuators": {"knee": {"model": "dynamixel_mx64"}}},
     "actuators.knee", "unknown key"),
    ("copper_loss without actuators", {"allocation": {"objective": "copper_loss"}},
     "allocation.objective", "actuators"),
    ("regeneration above 1", {"actuators": {"default": {"model": "dynamixel_mx64",
                                                        "regeneration": 1.5}}},
     "actuators.default.regeneration", "got 1.5"),
]


def part_e(d):
    for i, (what, body, key, word) in enumerate(BAD):
        path = scene(d, f"bad_{i}.yaml", body)
        out = os.path.join(d, f"bad_{i}.h5")
        kept = os.path.join(d, "kept.h5")  # an existing output: refused input leaves it as it is
        with open(kept, "wb") as f:
            f.write(b"not overwritten")
        p = subprocess.run([HEXDYN, "run", path, "-o", out], capture_output=True, text=True)
        q = subprocess.run([HEXDYN, "run", path, "-o", kept], capture_output=True, text=True)
        lines = p.stderr.splitlines()
        assert p.returncode == 2, f"{what}: exit {p.returncode}: {p.stderr}"
        assert len(lines) == 1, f"{what}: {len(lines)} lines on stderr: {p.stderr}"
        assert re.search(rf"\b{re.escape(key)}: ", lines[0]), f"{what}: {key} not named: {lines[0]}"
        assert word in lines[0], f"{what}: '{word}' not in: {lines[0]}"
        assert not os.path.exists(out), f"{what}: {out} written"
        assert q.returncode == 2 and q.stderr == p.stderr.replace(out, kept), (what, q.stderr)
        with open(kept, "rb") as f:
            assert f.read() == b"not overwritten", f"{what}: an existing output overwritten"
        left = [n for n in os.listdir(d) if n.startswith(f"bad_{i}.h5")]
        assert not left, f"{what}: {left} left"
        print(f"e. {what}: {lines[0]}")


with tempfile.TemporaryDirectory() as tmp:
    for part in (part_a, part_b, part_c, part_d, part_e):
        work = os.path.join(tmp, part.__name__)
        os.mkdir(work)
        part(work)
print("drive train: ok")
