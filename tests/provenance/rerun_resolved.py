#!/usr/bin/python3
"""Provenance that reruns (docs/user/configuration.md#automatic-choices-in-the-resolved-configuration):
a scene with automatic choices is run, its /meta config_yaml is extracted to a file in
another folder, and that file is run again with `hexdyn run`. Every dataset of the two
results must be equal bit for bit, except /solver/seconds (timing); every attribute must be
equal except /meta created_utc and wall_time_s (timing) and input_sha256 (the second run
reads another scene file: its URDF lines must be equal). The resolved configuration of
the second run must equal the first's: running it again pins nothing new.

The scenes: configs/sweeps/stairs_base.yaml (inherits configs/paper.yaml; automatic
posture height and foot spread), configs/robots/kraby_stairs.yaml (a URDF robot,
automatic posture) and the same with gait.foot_lateral left out (its default: the URDF's
nominal stance radius), configs/paper.yaml (allocation.solver: auto), and a design of
configs/designs/paper_base.yaml with longer or shorter links (robot.links_follow_length:
the stretched masses and the femur's default COM).

    rerun_resolved.py HEXDYN SOURCE_DIR WORK_DIR
"""
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np
import yaml

TIMING_DATASETS = {"/solver/seconds"}
TIMING_META = {"created_utc", "wall_time_s"}


def fail(message):
    print(f"FAILED: {message}", file=sys.stderr)
    sys.exit(1)


def run(hexdyn, scene, out):
    p = subprocess.run([hexdyn, "run", scene, "-o", out], capture_output=True, text=True)
    if p.returncode != 0:
        fail(f"hexdyn run {scene}: exit {p.returncode}: {p.stderr.strip()}")


def collect(f):
    datasets, attributes = {}, {}

    def visit(name, obj):
        path = "/" + name
        for key, value in obj.attrs.items():
            # Dimension-scale links are object references (file addresses), which move when
            # /meta's paths differ in length; compare the dimension names they stand for.
            if key in ("DIMENSION_LIST", "REFERENCE_LIST"):
                continue
            attributes[(path, key)] = value
        if isinstance(obj, h5py.Dataset):
            attributes[(path, "dimensions")] = tuple(
                tuple(s.name for s in d.values()) for d in obj.dims)
        if isinstance(obj, h5py.Dataset):
            datasets[path] = obj[()]

    f.visititems(visit)
    return datasets, attributes


def same_bits(a, b):
    a, b = np.asarray(a), np.asarray(b)
    if a.dtype != b.dtype or a.shape != b.shape:
        return False
    if a.dtype.kind == "O":
        return all(x == y for x, y in zip(a.ravel(), b.ravel()))
    return a.tobytes() == b.tobytes()


def urdf_lines(text):
    return sorted(line.split("  ", 1)[0] for line in text.splitlines() if line.endswith(".urdf"))


def compare(first, second, label):
    with h5py.File(first, "r") as f, h5py.File(second, "r") as g:
        d1, a1 = collect(f)
        d2, a2 = collect(g)
    if set(d1) != set(d2):
        fail(f"{label}: datasets differ: {sorted(set(d1) ^ set(d2))}")
    compared = 0
    for path in sorted(d1):
        if path in TIMING_DATASETS:
            continue
        if not same_bits(d1[path], d2[path]):
            fail(f"{label}: {path} differs between the run and its rerun")
        compared += 1
    if set(a1) != set(a2):
        fail(f"{label}: attributes differ: {sorted(set(a1) ^ set(a2))}")
    for key in sorted(a1):
        path, name = key
        if path == "/meta" and name in TIMING_META | {"input_sha256"}:
            continue
        if not same_bits(a1[key], a2[key]):
            fail(f"{label}: attribute {path} {name} differs between the run and its rerun")
    if urdf_lines(a1[("/meta", "input_sha256")]) != urdf_lines(a2[("/meta", "input_sha256")]):
        fail(f"{label}: the URDF's SHA-256 differs between the run and its rerun")
    return compared


def main():
    hexdyn, src, work = sys.argv[1], os.path.abspath(sys.argv[2]), sys.argv[3]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(os.path.join(work, "elsewhere"))
    kraby = os.path.join(src, "configs/robots/kraby_stairs.yaml")
    # Kraby with gait.foot_lateral left out: the URDF's stance radius is the default.
    with open(kraby) as f:
        tree = yaml.safe_load(f)
    del tree["gait"]["foot_lateral"]
    tree["robot"]["urdf"] = os.path.join(src, "robots/kraby.urdf")
    kraby_default = os.path.join(work, "kraby_default_spread.yaml")
    with open(kraby_default, "w") as f:
        yaml.safe_dump(tree, f)
    # A design whose links follow their length (robot.links_follow_length): stretched femur
    # and tibia, the femur's COM left to its default (the reference's mid-length, stretched).
    design = os.path.join(work, "design_stretched.yaml")
    with open(design, "w") as f:
        yaml.safe_dump({"inherit": os.path.join(src, "configs/designs/paper_base.yaml"),
                        "robot": {"femur": {"length": 0.15, "com": None},
                                  "tibia": {"length": 0.08}}}, f)
    scenes = {
        "stairs_base": os.path.join(src, "configs/sweeps/stairs_base.yaml"),
        "design_stretched": design,
        "kraby": kraby,
        "kraby_default_spread": kraby_default,
        "paper": os.path.join(src, "configs/paper.yaml"),
    }
    for label, scene in scenes.items():
        first = os.path.join(work, label + ".h5")
        run(hexdyn, scene, first)
        with h5py.File(first, "r") as f:
            resolved = f["meta"].attrs["config_yaml"]
        config = yaml.safe_load(resolved)
        requests = config.get("auto", {})
        if label != "paper":
            posture = config["motion"]["posture"]
            if not isinstance(posture.get("height"), float):
                fail(f"{label}: motion.posture.height is {posture.get('height')!r}, expected the height used")
            if requests.get("motion", {}).get("posture", {}).get("height") != "auto":
                fail(f"{label}: auto.motion.posture.height does not keep the request 'auto'")
        if label == "kraby_default_spread" and requests.get("gait", {}).get("foot_lateral") != "auto":
            fail(f"{label}: auto.gait.foot_lateral does not record the URDF's default")
        if config["allocation"]["solver"] != "active-set" or requests["allocation"]["solver"] != "auto":
            fail(f"{label}: allocation.solver auto is not resolved beside its request")
        # The resolved configuration run from another folder.
        extracted = os.path.join(work, "elsewhere", label + "_resolved.yaml")
        with open(extracted, "w") as f:
            f.write(resolved)
        second = os.path.join(work, "elsewhere", label + "_rerun.h5")
        run(hexdyn, extracted, second)
        n = compare(first, second, label)
        with h5py.File(second, "r") as g:
            if g["meta"].attrs["config_yaml"] != resolved:
                fail(f"{label}: the rerun's resolved configuration differs from the first run's")
        print(f"{label}: {n} datasets equal bit for bit after the rerun")


if __name__ == "__main__":
    main()
