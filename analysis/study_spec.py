#!/usr/bin/python3
"""The study file of analysis/study.py (hexdyn-study/1 input): reading and checking it, every
key with its path in the error, and the canonical text of the values a run sets. Imported by
study.py; not a program of its own."""

import itertools
import math
import os
import sys

import yaml

CONVERGED = "converged"


class StudyError(Exception):
    """One-line error; `status` is the exit status."""

    def __init__(self, message, status=2):
        super().__init__(message)
        self.status = status


def log(msg, quiet=False):
    if not quiet:
        print(f"study: {msg}", file=sys.stderr, flush=True)


# ---------------------------------------------------------------- study file


def parse_number(value):
    """float for numbers and numeric strings (PyYAML reads 1e-4 as a string), else None."""
    if isinstance(value, bool):
        return None
    if isinstance(value, (int, float)):
        return float(value)
    if isinstance(value, str):
        try:
            return float(value)
        except ValueError:
            return None
    return None


def canonical(value):
    """A comparable form of a --set value: numbers as float, the rest as text."""
    n = parse_number(value)
    if n is not None:
        return n
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


def set_text(value):
    """The --set text of a value (hexdyn parses it as YAML)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, (list, tuple)):
        return "[" + ",".join(set_text(v) for v in value) + "]"
    return str(value)


def _check_keys(where, mapping, allowed, required=(), top=False):
    if not isinstance(mapping, dict):
        raise StudyError(f"{where}: expected a mapping, got {type(mapping).__name__}")
    for k in mapping:
        if k not in allowed:
            raise StudyError(f"{where}{': ' if top else '.'}{k}: unknown key, allowed here: "
                             f"{', '.join(allowed)}")
    for k in required:
        if k not in mapping:
            raise StudyError(f"{where}: missing key '{k}'")


def _check_set(where, mapping):
    if mapping is None:
        return {}
    if not isinstance(mapping, dict):
        raise StudyError(f"{where}: expected a mapping of dotted scene keys to values")
    for k, v in mapping.items():
        if not isinstance(k, str) or not k or "." not in k:
            raise StudyError(f"{where}: key {k!r} is not a dotted scene key (e.g. output.grid)")
        if isinstance(v, dict) or v is None:
            raise StudyError(f"{where}.{k}: got {v!r}, expected a value")
    return dict(mapping)


def _positive(where, value, integer=False):
    n = parse_number(value)
    if n is None or not math.isfinite(n) or n <= 0 or (integer and n != int(n)):
        raise StudyError(f"{where}: got {value!r}, expected a positive "
                         f"{'integer' if integer else 'number'}")
    return int(n) if integer else n


def load_study(path):
    """The validated study definition (dict)."""
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except OSError as e:
        raise StudyError(f"{path}: cannot read the study file: {e.strerror}")
    try:
        spec = yaml.safe_load(text)
    except yaml.YAMLError as e:
        raise StudyError(f"{path}: not valid YAML: {str(e).splitlines()[0]}")
    _check_keys(path, spec, ("scene", "targets", "repeats", "references", "series"),
                ("scene", "targets", "repeats", "references", "series"), top=True)
    if not isinstance(spec["scene"], str):
        raise StudyError(f"{path}: scene: expected a file name")
    scene = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(path)), spec["scene"]))

    targets = spec["targets"]
    _check_keys(f"{path}: targets", targets, ("peak", "energy", "cost"), ("peak", "energy", "cost"))
    targets = {k: _positive(f"{path}: targets.{k}", v) for k, v in targets.items()}

    rep = spec["repeats"]
    _check_keys(f"{path}: repeats", rep, ("fast", "slow", "slow_s", "paired"), ("fast", "slow", "slow_s"))
    repeats = {"fast": _positive(f"{path}: repeats.fast", rep["fast"], integer=True),
               "slow": _positive(f"{path}: repeats.slow", rep["slow"], integer=True),
               "slow_s": _positive(f"{path}: repeats.slow_s", rep["slow_s"]),
               "paired": (_positive(f"{path}: repeats.paired", rep["paired"], integer=True)
                          if "paired" in rep else 0)}

    refs = spec["references"]
    if not isinstance(refs, dict) or CONVERGED not in refs:
        raise StudyError(f"{path}: references: expected a mapping with at least '{CONVERGED}'")
    references = {}
    for name, r in refs.items():
        where = f"{path}: references.{name}"
        _check_keys(where, r, ("set", "check"), ("set",))
        references[str(name)] = {"set": _check_set(f"{where}.set", r["set"]),
                                 "check": _check_set(f"{where}.check", r.get("check"))
                                 if r.get("check") is not None else None}

    if not isinstance(spec["series"], list) or not spec["series"]:
        raise StudyError(f"{path}: series: expected a non-empty list")
    series = []
    for i, s in enumerate(spec["series"]):
        where = f"{path}: series[{i}]"
        _check_keys(where, s, ("category", "reference", "set", "sweep", "runs"), ("category",))
        category = s["category"]
        if not isinstance(category, str) or not category:
            raise StudyError(f"{where}.category: expected a name")
        where = f"{path}: series[{i}] ({category})"
        reference = s.get("reference", CONVERGED)
        if reference not in references:
            raise StudyError(f"{where}.reference: got {reference!r}, expected one of "
                             f"{', '.join(references)}")
        common = _check_set(f"{where}.set", s.get("set"))
        if ("sweep" in s) == ("runs" in s):
            raise StudyError(f"{where}: expected exactly one of 'sweep' and 'runs'")
        runs = []
        if "sweep" in s:
            sweep = s["sweep"]
            if not isinstance(sweep, dict) or not sweep:
                raise StudyError(f"{where}.sweep: expected a mapping of keys to lists of values")
            keys = list(sweep)
            for k in keys:
                _check_set(f"{where}.sweep", {k: 0})
                if not isinstance(sweep[k], list) or not sweep[k]:
                    raise StudyError(f"{where}.sweep.{k}: expected a non-empty list of values")
            for combo in itertools.product(*(sweep[k] for k in keys)):
                sets = dict(common)
                sets.update(zip(keys, combo))
                label = ", ".join(f"{k.split('.')[-1]}={set_text(v)}" for k, v in zip(keys, combo))
                runs.append({"label": label, "set": sets})
        else:
            if not isinstance(s["runs"], list) or not s["runs"]:
                raise StudyError(f"{where}.runs: expected a non-empty list")
            for j, r in enumerate(s["runs"]):
                _check_keys(f"{where}.runs[{j}]", r, ("label", "set"), ("label", "set"))
                sets = dict(common)
                sets.update(_check_set(f"{where}.runs[{j}].set", r["set"]))
                runs.append({"label": str(r["label"]), "set": sets})
        labels = [r["label"] for r in runs]
        if len(set(labels)) != len(labels):
            raise StudyError(f"{where}: two runs have the same label")
        series.append({"category": category, "reference": reference, "runs": runs})
    return {"path": path, "text": text, "scene": scene, "targets": targets,
            "repeats": repeats, "references": references, "series": series}


# ---------------------------------------------------------------- runs
