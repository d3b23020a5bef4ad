#!/usr/bin/python3
"""Fuzz test of hexdyn's input handling: seeded random mutations of
configs/paper.yaml and of a sweep file, each run through `hexdyn validate`, `run` or
`sweep`. Every mutation must

  - exit with 0, 2 (bad input) or 3 (a scene that cannot be computed), never crash,
    hang or exit 4 (internal error), within --time-limit seconds;
  - on 2 or 3: print its last stderr line as "hexdyn: error: ...", create no output file
    and leave every input file unchanged;
  - on 0: leave the inputs unchanged and, when it wrote a file, write one without NaN in
    any float dataset (h5py).

    /usr/bin/python3 tests/fuzz/fuzz_configs.py --hexdyn build/hexdyn [--count N] [--seed S]

The count defaults to $HEXDYN_FUZZ_COUNT or 240; mutation i uses the seed S + i, so one
mutation is reproduced with --seed S+i --count 1. A failing mutation prints its seed,
what was mutated and the mutated file. Scenes for `run` are made cheap first (uniform
grid, 0.5 s samples) so that a few hundred mutations take about a minute.
"""

import argparse
import copy
import os
import random
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np
import yaml

EXTREME_NUMBERS = [0, -1, 1e-300, -1e-300, 1e-9, 1e300, -1e300, 1e6, 2 ** 31, -(2 ** 63),
                   0.5, 0.99999, 1.0, 3, ".nan", ".inf", "-.inf", "1/3", "3/0", "0x1F", "1e", "++1"]
ODD_VALUES = ["", "abc", "é∂ƒ漢字", "\U0001F600", "null", "~", "true", "[1, 2", "{a: 1}", [], [1, 2, 3],
              [[1]], {}, {"x": 1}, None, True, "a" * 5000, "  ", "0.5.5", "- 1"]
OK_EXITS = {0, 2, 3}


def load_yaml(path):
    with open(path, encoding="utf-8") as f:
        return yaml.safe_load(f)


def dump(tree):
    return yaml.safe_dump(tree, allow_unicode=True, sort_keys=False, default_flow_style=None)


def key_paths(node, prefix=()):
    """Every (path tuple) of a map key in the tree, maps inside lists included."""
    out = []
    if isinstance(node, dict):
        for k, v in node.items():
            out.append(prefix + (k,))
            out.extend(key_paths(v, prefix + (k,)))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            out.extend(key_paths(v, prefix + (i,)))
    return out


def parent_of(tree, path):
    node = tree
    for k in path[:-1]:
        node = node[k]
    return node


def nested(depth, leaf):
    for i in range(depth):
        leaf = [leaf] if i % 2 else {"k": leaf}
    return leaf


def random_value(rng):
    r = rng.random()
    if r < 0.45:
        return rng.choice(EXTREME_NUMBERS)
    if r < 0.85:
        return copy.deepcopy(rng.choice(ODD_VALUES))
    return nested(rng.randint(2, 200), rng.choice([1, "x", None]))


def mutate_tree(tree, rng):
    """One structural mutation of a YAML tree; returns (text, description)."""
    tree = copy.deepcopy(tree)
    paths = key_paths(tree)
    path = rng.choice(paths)
    parent, key = parent_of(tree, path), path[-1]
    kind = rng.choice(["scale", "scale", "scale", "value", "value", "value", "delete", "retype", "rename", "swap", "move",
                       "unicode_key", "nest", "list_len", "top"])
    if kind == "scale":
        numbers = [p for p in paths if isinstance(parent_of(tree, p)[p[-1]], (int, float))
                   and not isinstance(parent_of(tree, p)[p[-1]], bool)]
        if numbers:
            path = rng.choice(numbers)
            parent, key = parent_of(tree, path), path[-1]
        factor = rng.choice([0.5, 0.9, 1.1, 2.0, 10.0, 0.1, 1e-3, 1e3, -1.0])
        if isinstance(parent[key], (int, float)) and not isinstance(parent[key], bool):
            parent[key] = parent[key] * factor
        what = f"{'.'.join(map(str, path))} x {factor}"
    elif kind == "value":
        parent[key] = random_value(rng)
        what = f"{'.'.join(map(str, path))} = {str(parent[key])[:80]!r}"
    elif kind == "delete":
        del parent[key]
        what = f"delete {'.'.join(map(str, path))}"
    elif kind == "retype":
        v = parent[key]
        parent[key] = rng.choice([[v], {"value": v}, str(v), None, [v, v]])
        what = f"retype {'.'.join(map(str, path))} -> {type(parent[key]).__name__}"
    elif kind == "rename":
        parent[str(key) + rng.choice(["_x", "s", "é", " ", ".y"])] = parent.pop(key)
        what = f"rename {'.'.join(map(str, path))}"
    elif kind == "swap":
        top = [k for k in tree if isinstance(tree[k], dict)]
        if len(top) >= 2:
            a, b = rng.sample(top, 2)
            tree[a], tree[b] = tree[b], tree[a]
            what = f"swap sections {a} and {b}"
        else:
            what = "swap (nothing to swap)"
    elif kind == "move":
        v = parent.pop(key)
        sections = [k for k in tree if isinstance(tree[k], dict)] or [None]
        target = rng.choice(sections)
        (tree[target] if target is not None else tree)[key] = v
        what = f"move {'.'.join(map(str, path))} into {target}"
    elif kind == "unicode_key":
        parent["ключ_" + rng.choice(["π", "漢", "\u200b", "e\u0301"])] = 1
        what = "add a unicode key"
    elif kind == "nest":
        parent[key] = nested(rng.randint(10, 120), parent[key])
        what = f"nest {'.'.join(map(str, path))}"
    elif kind == "list_len":
        v = parent[key]
        parent[key] = (v * rng.randint(2, 50)) if isinstance(v, list) else [v] * rng.randint(0, 5)
        what = f"list length of {'.'.join(map(str, path))}"
    else:  # the top level replaced
        tree = rng.choice([[tree], "scalar", None, 42])
        what = f"top level -> {type(tree).__name__}"
    return dump(tree), what


def mutate_text(text, rng):
    """One line-level mutation: duplicates, deletions, stray syntax, bytes."""
    lines = text.splitlines(keepends=True)
    i = rng.randrange(len(lines))
    kind = rng.choice(["dup_line", "dup_line", "del_line", "tab", "doc", "cut", "byte", "anchor"])
    if kind == "dup_line":
        lines.insert(i + 1, lines[i])
        what = f"duplicate line {i + 1}: {lines[i].strip()[:60]!r}"
    elif kind == "del_line":
        what = f"delete line {i + 1}: {lines.pop(i).strip()[:60]!r}"
    elif kind == "tab":
        lines[i] = "\t" + lines[i]
        what = f"tab before line {i + 1}"
    elif kind == "doc":
        lines.insert(i, "---\n")
        what = f"'---' before line {i + 1}"
    elif kind == "cut":
        cut = rng.randrange(len(text))
        return text[:cut], f"truncate at byte {cut}"
    elif kind == "anchor":
        lines.insert(i, "x: &a [*a]\n" if rng.random() < 0.5 else "<<: {a: 1}\n")
        what = f"anchor/merge key before line {i + 1}"
    else:
        data = bytearray(text.encode("utf-8"))
        j = rng.randrange(len(data))
        data[j] = rng.choice([0x00, 0xff, 0x7b, 0x3a, 0x22, 0xc3])
        return data.decode("utf-8", errors="replace"), f"byte {j} replaced"
    return "".join(lines), what


# /scenarios metrics that are NaN by contract in a computed row too (docs/user/output.md):
# the drive train's without actuators, a split peak without a sample of its kind (no
# touchdown transient), the thermal load without a continuous rating, the grip metrics
# without a finite required friction of their kind (or with output.required_friction false)
# and the utilised friction of a foot that pulls (+inf), and a robustness study's success
# fraction and interval without a study (docs/user/robustness.md#in-a-sweep).
NAN_BY_CONTRACT = {
    "scenarios/" + name for name in (
        "energy_electrical", "energy_copper_loss", "energy_friction_loss", "energy_regenerated",
        "cost_of_transport_electrical", "peak_electrical_power", "peak_drive_torque_gait",
        "peak_drive_torque_transient", "drive_torque_window_rms", "thermal_load",
        "peak_torque_gait", "peak_torque_transient", "required_friction_support",
        "required_friction_support_time", "required_friction_transient",
        "required_friction_transient_time", "peak_utilized_friction", "p_success",
        "p_success_low", "p_success_high")}
# Result datasets NaN by contract (docs/theory/grip.md): the utilised friction of a swing leg
# (and where a relaxed sample's force does not press the foot), the required friction where no
# mu suffices; also in a kept run's group. Never infinite.
NAN_BY_CONTRACT_RESULT = ("contacts/utilized_friction", "contacts/required_friction")
# Datasets that may hold NaN (a joint without a thermal model, a row without one) and +inf (a
# winding that never reaches its limit) by contract (docs/theory/drive-train.md#thermal-model).
INF_BY_CONTRACT = ("scenarios/peak_winding_temperature", "scenarios/time_to_winding_limit",
                   "scenarios/peak_winding_temperature_max", "scenarios/time_to_winding_limit_min",
                   "thermal/winding_temperature", "thermal/housing_temperature",
                   "thermal/peak_winding_temperature", "thermal/time_to_limit",
                   "thermal/peak", "thermal/first_time_to_limit")


def nan_free(path):
    """None if every float dataset of an HDF5 file is finite, else the first bad path. In
    a sweep file the metrics of scenarios that were not computed (status != 0) are NaN by
    contract (docs/user/sweeps.md); only the computed rows are checked there, and not the
    metrics of NAN_BY_CONTRACT, which may be NaN in a computed row."""
    import h5py
    bad = []

    def visit(name, obj):
        if bad or not isinstance(obj, h5py.Dataset) or obj.dtype.kind != "f":
            return
        data = obj[()]
        if name.endswith(INF_BY_CONTRACT):
            return
        if name in NAN_BY_CONTRACT or name.endswith(NAN_BY_CONTRACT_RESULT):
            if np.any(np.isinf(data)):
                bad.append(name)
            return
        if name.startswith("scenarios/") and ok_rows is not None and np.ndim(data) >= 1 \
                and len(data) == len(ok_rows):
            data = data[ok_rows]
        if not np.all(np.isfinite(data)):
            bad.append(name)

    with h5py.File(path, "r") as f:
        ok_rows = np.asarray(f["scenarios/status"][()]) == 0 if "scenarios/status" in f else None
        f.visititems(visit)
    return bad[0] if bad else None


def snapshot(folder):
    out = {}
    for root, _, files in os.walk(folder):
        for name in files:
            p = os.path.join(root, name)
            with open(p, "rb") as f:
                out[os.path.relpath(p, folder)] = f.read()
    return out


class Fuzzer:
    def __init__(self, args):
        self.args = args
        self.paper_text = open(os.path.join(args.source, "configs", "paper.yaml"), encoding="utf-8").read()
        self.paper = yaml.safe_load(self.paper_text)
        cheap = copy.deepcopy(self.paper)
        cheap["output"].update({"grid": "uniform", "sample_step": 0.5})
        self.cheap = cheap
        self.sweep = {"name": "fuzz", "base": "base.yaml",
                      "set": {"output.grid": "uniform", "output.sample_step": 0.5},
                      "axes": [{"key": "gait.duty_factor", "values": ["1/2", "3/4"]},
                               {"key": "terrain.riser_height", "range": {"from": 0.03, "to": 0.05, "count": 2}}]}
        self.env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                        OMPI_MCA_rmaps_base_oversubscribe="1")
        self.failures = 0

    def case(self, seed):
        """(files {name: text}, argv, description) of mutation `seed`."""
        rng = random.Random(seed)
        sweep = rng.random() < 0.25
        command = "validate" if rng.random() < 0.7 else ("sweep" if sweep else "run")
        if sweep:
            tree, target = self.sweep, "sweep.yaml"
        else:
            tree, target = (self.cheap if command == "run" else self.paper), "scene.yaml"
        base_text = dump(tree)
        text, what = mutate_tree(tree, rng) if rng.random() < 0.7 else mutate_text(base_text, rng)
        if rng.random() < 0.3:  # a second mutation on top
            more, what2 = mutate_text(text, rng) if text.strip() else (text, "")
            text, what = more, what + "; " + what2
        files = {target: text}
        if sweep:
            files["base.yaml"] = dump(self.cheap)
        argv = [command, target]
        if command != "validate":
            argv += ["-o", "out.h5"]
        return files, argv, f"{command} {target}: {what}"

    def check(self, seed):
        files, argv, what = self.case(seed)
        work = tempfile.mkdtemp(prefix="hexdyn_fuzz_")
        try:
            for name, text in files.items():
                with open(os.path.join(work, name), "w", encoding="utf-8", errors="surrogateescape") as f:
                    f.write(text)
            before = snapshot(work)
            t0 = time.monotonic()
            try:
                p = subprocess.run([self.args.hexdyn] + argv, cwd=work, env=self.env, capture_output=True,
                                   timeout=self.args.time_limit, text=True, errors="replace")
                rc, err = p.returncode, p.stderr
            except subprocess.TimeoutExpired:
                rc, err = None, ""
            elapsed = time.monotonic() - t0
            problems = []
            if rc is None:
                problems.append(f"no exit within {self.args.time_limit} s")
            elif rc not in OK_EXITS:
                problems.append(f"exit status {rc}")
            after = snapshot(work)
            out = os.path.join(work, "out.h5")
            for name, data in before.items():
                if after.get(name) != data:
                    problems.append(f"input {name} changed")
            if rc in (2, 3):
                last = err.strip().splitlines()[-1] if err.strip() else ""
                if not last.startswith("hexdyn: error: "):
                    problems.append(f"last stderr line is not 'hexdyn: error: ...': {last[:200]!r}")
                if set(after) != set(before):
                    problems.append(f"files created: {sorted(set(after) - set(before))}")
            if rc == 0 and os.path.exists(out):
                bad = nan_free(out)
                if bad:
                    problems.append(f"NaN or infinity in {bad}")
            if problems:
                self.failures += 1
                print(f"FAIL seed {seed}: {what}\n  " + "\n  ".join(problems) +
                      f"\n  command: hexdyn {' '.join(argv)} (exit {rc}, {elapsed:.1f} s)\n  stderr: {err.strip()[-600:]}")
                for name, text in files.items():
                    print(f"  --- {name} ---\n{text[:4000]}")
            return rc, elapsed
        finally:
            shutil.rmtree(work, ignore_errors=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--hexdyn", required=True, help="the hexdyn binary")
    parser.add_argument("--source", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."),
                        help="source tree (for configs/paper.yaml)")
    parser.add_argument("--count", type=int, default=int(os.environ.get("HEXDYN_FUZZ_COUNT", "240")))
    parser.add_argument("--seed", type=int, default=int(os.environ.get("HEXDYN_FUZZ_SEED", "1300")))
    parser.add_argument("--time-limit", type=float, default=20.0, help="seconds per mutation")
    args = parser.parse_args()
    args.hexdyn = os.path.abspath(args.hexdyn)
    fuzz = Fuzzer(args)
    exits = {}
    t0 = time.monotonic()
    slowest = (0.0, None)
    for i in range(args.count):
        rc, elapsed = fuzz.check(args.seed + i)
        exits[rc] = exits.get(rc, 0) + 1
        slowest = max(slowest, (elapsed, args.seed + i))
    print(f"fuzz_configs: {args.count} mutations (seeds {args.seed}..{args.seed + args.count - 1}) in "
          f"{time.monotonic() - t0:.0f} s, exits {dict(sorted(exits.items(), key=str))}, slowest "
          f"{slowest[0]:.1f} s (seed {slowest[1]}), {fuzz.failures} failed")
    return 1 if fuzz.failures else 0


if __name__ == "__main__":
    sys.exit(main())
