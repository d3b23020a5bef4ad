#!/usr/bin/python3
"""The speed-against-error study: runs the paper scene across output grids, physics
fidelity choices and solver tolerances, and measures each run's cost and its error
against a converged reference. Writes one `hexdyn-study/1` HDF5 file.

    /usr/bin/python3 analysis/study.py [STUDY.yaml] [-o results/study/study.h5]
        [--hexdyn build/hexdyn] [--keep-runs DIR] [-q]

STUDY.yaml (default configs/study/study.yaml; configs/study/quick.yaml is the reduced
study) names the scene, the references, the series of runs and the repeats; its
comments give the reasoning behind the choices. Every run is
`hexdyn run SCENE -o FILE --set key=value ...` in a temporary directory, sequentially
(runs in parallel would disturb each other's timing), with a copy of the hexdyn binary
taken at the start, so that a rebuild during the study cannot mix two builds.

Metrics of a run (each against the reference named in its row, same touchdowns):
  err_peak      for each touchdown of the reference (/impacts/leg, t_start, duration),
                the largest sampled normal force of that leg in [t_start, t_start +
                duration) on the run's output grid, relative to the reference's;
                the worst touchdown. The normal force is the z component of
                /contacts/force: feet touch down on treads (or flat ground), whose
                normal is +z. The window is half-open: at t_start + duration the
                transient has ended and the sample there is a support sample carrying
                the allocated (not the impact) force. No sample in the window = a
                sampled peak of 0 (100 % error): that is what the output shows. For a
                rigid contact (no transient) the samples in the window are support
                samples; their force is compared as it is.
  err_impulse   trapezoid of the same sampled normal force over the samples in the
                window (0 with fewer than two), relative, worst touchdown.
  err_energy    /energy/total (= integral of sum |tau omega| dt), relative.
  err_tau_peak  max over joints and samples of |tau|, relative.
  err_tau_rms   sqrt(trapezoid of sum_k tau_k^2 / J over time / duration), relative (J
                joints).
  wall_time_s   the smallest /meta wall_time_s (compute time, file writing excluded)
                over the run's repeats.
Runs that differ from the scene by nothing (after dropping --set values equal to the
scene's) are computed once and may appear in several rows (e.g. the default is also
in the grid and tolerance series).

The verdict (the study's targets for the adaptive grid) is the default configuration (the
scene as it is) against the `converged` reference: err_peak <= targets.peak,
err_energy <= targets.energy and wall_time(default) / wall_time(reference) <=
targets.cost. With `repeats.paired: N` the two wall times of the verdict come from N
further runs of each, alternating default and reference at the end of the study
(minimum of each), so that a machine whose speed drifts during the study (other jobs,
clock changes) moves both sides of the ratio alike.

Output, hexdyn-study/1 (written to a temporary name in the same directory, renamed
when complete; an error leaves no file):
  /meta attrs        schema, schema_version, created_utc, hexdyn_version, git_commit
                     (of the hexdyn build), study_file, study_yaml, scene_file,
                     scene_yaml, hexdyn_processes, study_wall_time_s
  /runs/<column>     one row per run: label, category, reference, overrides, grid,
                     solver (effective: auto resolved), friction, leg_inertia,
                     contact_model (strings); sample_step, event_step, tolerance,
                     wall_time_s, energy_J, tau_peak_Nm, tau_rms_Nm, err_peak,
                     err_impulse, err_energy, err_tau_peak, err_tau_rms (float64);
                     impact_samples, samples, relaxed_samples, failed_samples, repeats
                     (int32); impacts_match (int8: 1 the run's /impacts are the
                     reference's touchdowns, 0 they differ, -1 the run has none);
                     is_default (int8). Every dataset has a `units` attribute.
  /references/<name> attrs: overrides, samples, wall_time_s, repeats, energy_J,
                     tau_peak_Nm, tau_rms_Nm; for a reference with a check run also
                     check_overrides, check_samples, check_wall_time_s and the floor:
                     floor_err_peak, floor_err_impulse, floor_err_energy,
                     floor_err_tau_peak, floor_err_tau_rms (the check run against the
                     reference). Datasets impact_leg, impact_t_start, impact_duration,
                     sampled_peak_N, sampled_impulse_Ns (one per touchdown).
  /verdict attrs     label, reference, err_peak, err_energy, wall_time_s,
                     reference_wall_time_s, cost_ratio, cost_pairs (0: wall times
                     of the rows), samples, reference_samples,
                     samples_ratio, target_peak, target_energy, target_cost, pass_peak,
                     pass_energy, pass_cost, pass_all (int8 0/1)

Exit status: 0 written; 2 bad input (study file, scene keys, binary, output path),
nothing run; 1 a hexdyn run failed or another error during the study, nothing written.
"""

import argparse
import datetime
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time


import h5py  # noqa: E402
import numpy as np  # noqa: E402
import yaml  # noqa: E402

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from hexdyn import results as hr  # noqa: E402
from study_spec import (  # noqa: E402  (this folder: the study file)
    CONVERGED, StudyError, parse_number, canonical, load_study, log, set_text)

STUDY_SCHEMA = "hexdyn-study/1"
STUDY_SCHEMA_VERSION = 1
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_STUDY = os.path.join(ROOT, "configs", "study", "study.yaml")
DEFAULT_OUTPUT = os.path.join(ROOT, "results", "study", "study.h5")
DEFAULT_LABEL = "default"
EPS_T = 1e-9  # s: hexdyn merges grid points closer than this
_trapz = getattr(np, "trapezoid", None) or np.trapz  # numpy 2 renamed trapz
ERROR_METRICS = ("err_peak", "err_impulse", "err_energy", "err_tau_peak", "err_tau_rms")


def _scene_lookup(scene, dotted):
    node = scene
    for part in dotted.split("."):
        if not isinstance(node, dict) or part not in node:
            return None
        node = node[part]
    return node


class RunSpec:
    """One distinct hexdyn run: the --set overrides that differ from the scene."""

    def __init__(self, sets, scene):
        sets = dict(sets)
        # On a uniform grid event_step is unused, but hexdyn requires it <= sample_step.
        grid = sets.get("output.grid", _scene_lookup(scene, "output.grid"))
        step = parse_number(sets.get("output.sample_step", _scene_lookup(scene, "output.sample_step")))
        event = parse_number(sets.get("output.event_step", _scene_lookup(scene, "output.event_step")))
        if grid == "uniform" and step is not None and event is not None and event > step:
            sets["output.event_step"] = step
        self.sets = {k: v for k, v in sorted(sets.items())
                     if _scene_lookup(scene, k) is None
                     or canonical(_scene_lookup(scene, k)) != canonical(v)}
        self.key = tuple((k, canonical(v)) for k, v in self.sets.items())
        self.args = [f"{k}={set_text(v)}" for k, v in self.sets.items()]
        self.name = None       # e.g. "converged" or the first row's label
        self.result = None     # Measured

    @property
    def overrides(self):
        return "; ".join(self.args)


def _tail(text):
    lines = [ln for ln in (text or "").strip().splitlines() if ln.strip()]
    return lines[-1] if lines else "(no message)"


def validate_run(hexdyn, scene, spec, where):
    cmd = [hexdyn, "validate", scene]
    for a in spec.args:
        cmd += ["--set", a]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise StudyError(f"{where}: the scene rejects the run's keys: {_tail(p.stderr)}")


def run_hexdyn(hexdyn, scene, spec, out):
    cmd = [hexdyn, "run", scene, "-o", out]
    for a in spec.args:
        cmd += ["--set", a]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise StudyError(f"run '{spec.name}' ({spec.overrides or 'no overrides'}) failed with "
                         f"exit status {p.returncode}: {_tail(p.stderr)}", status=1)


class Measured:
    """What the metrics need from one result file."""

    def __init__(self, path):
        with h5py.File(path, "r") as f:
            hr.check_filetype_version(f, hr.RESULT_SCHEMA, hr.RESULT_SCHEMA_VERSION, path)
            meta = f["meta"].attrs
            self.wall_time_s = float(meta["wall_time_s"])
            self.config = yaml.safe_load(hr.decode_text(meta["config_yaml"])) or {}
            self.version = hr.decode_text(meta.get("version", ""))
            self.git_commit = hr.decode_text(meta.get("git_commit", ""))
            self.t = f["/time"][()]
            self.fz = f["/contacts/force"][()][:, :, 2]  # (T, L): normal force on treads
            tau = f["/joints/torque"][()]
            self.energy = float(f["/energy/total"][()])
            self.impact_leg = f["/impacts/leg"][()].astype(int) + 1  # 1-based here
            self.impact_t0 = f["/impacts/t_start"][()]
            self.impact_duration = f["/impacts/duration"][()]
            status = f["/solver/status"][()]
        terrain = (self.config.get("terrain") or {}).get("type", "stairs")
        if terrain not in ("stairs", "flat"):
            raise StudyError(f"{path}: terrain type {terrain!r}: the normal force is taken as "
                             f"the z component, valid on treads and flat ground only", status=1)
        self.samples = len(self.t)
        self.relaxed = int(np.sum(status == 1))
        self.failed = int(np.sum(status == 2))
        self.tau_peak = float(np.max(np.abs(tau)))
        duration = self.t[-1] - self.t[0]
        self.tau_rms = float(math.sqrt(_trapz(np.sum(tau ** 2, axis=1) / tau.shape[1], self.t)
                                       / duration))
        self.wall_times = [self.wall_time_s]
        self.windows = {}  # reference name -> (sampled peaks, sampled impulses)

    def sample_windows(self, ref):
        """Sampled peak and impulse of this run in each touchdown window of `ref`."""
        peaks, impulses = [], []
        for leg, t0, dur in zip(ref.impact_leg, ref.impact_t0, ref.impact_duration):
            m = (self.t >= t0 - EPS_T) & (self.t < t0 + dur - EPS_T)
            fz = self.fz[m, leg - 1]
            peaks.append(float(fz.max()) if fz.size else 0.0)
            impulses.append(float(_trapz(fz, self.t[m])) if fz.size >= 2 else 0.0)
        return np.array(peaks), np.array(impulses)

    def impacts_match(self, ref):
        if len(self.impact_leg) == 0:
            return -1
        if len(self.impact_leg) != len(ref.impact_leg):
            return 0
        ok = (np.array_equal(self.impact_leg, ref.impact_leg)
              and np.allclose(self.impact_t0, ref.impact_t0, rtol=0, atol=EPS_T))
        return 1 if ok else 0

    def drop_arrays(self):
        self.t = self.fz = None


def rel(x, ref):
    x, ref = float(x), float(ref)
    if ref == 0.0:
        return 0.0 if x == 0.0 else math.inf
    return abs(x - ref) / abs(ref)


def worst_rel(xs, refs):
    if len(refs) == 0:
        return math.nan
    return max(rel(x, r) for x, r in zip(xs, refs))


def errors(run, ref_name, ref):
    peaks, impulses = run.windows[ref_name]
    ref_peaks, ref_impulses = ref.windows[ref_name]
    return {"err_peak": worst_rel(peaks, ref_peaks),
            "err_impulse": worst_rel(impulses, ref_impulses),
            "err_energy": rel(run.energy, ref.energy),
            "err_tau_peak": rel(run.tau_peak, ref.tau_peak),
            "err_tau_rms": rel(run.tau_rms, ref.tau_rms)}


def timed_run(hexdyn, scene, spec, out, counter):
    """One run of `spec` into `out`; its /meta wall_time_s."""
    run_hexdyn(hexdyn, scene, spec, out)
    counter[0] += 1
    with h5py.File(out, "r") as f:
        return float(f["meta"].attrs["wall_time_s"])


def timed_runs(specs, hexdyn, scene, workdir, rounds, counter):
    """Runs each of `specs` in turn, `rounds` times over; the smallest wall time of each."""
    out = os.path.join(workdir, "timed.h5")
    best = [math.inf] * len(specs)
    for _ in range(rounds):
        for k, spec in enumerate(specs):
            best[k] = min(best[k], timed_run(hexdyn, scene, spec, out, counter))
    os.remove(out)
    return best


def execute(spec, hexdyn, scene, workdir, repeats, keep_dir, quiet, counter, prefix=""):
    """Runs `spec` (repeated as `repeats` says) and returns its Measured."""
    out = os.path.join(workdir, "run.h5")
    walls = [timed_run(hexdyn, scene, spec, out, counter)]
    n = repeats["fast"] if walls[0] < repeats["slow_s"] else repeats["slow"]
    for _ in range(n - 1):
        walls.append(timed_run(hexdyn, scene, spec, out, counter))
    m = Measured(out)
    m.wall_times = walls
    m.wall_time_s = min(walls)
    if keep_dir:
        safe = "".join(c if c.isalnum() or c in "-_.=" else "_" for c in spec.name)
        shutil.copyfile(out, os.path.join(keep_dir, f"{safe}.h5"))
    os.remove(out)
    log(f"{prefix}{spec.name}: {m.samples} samples, {m.wall_time_s:.4g} s (min of {len(walls)}), "
        f"{m.relaxed} relaxed, {m.failed} failed", quiet)
    return m


# ---------------------------------------------------------------- output


def _config_get(config, dotted, default=None):
    v = _scene_lookup(config, dotted)
    return default if v is None else v


def describe(m):
    """Settings of a run from its resolved configuration."""
    c = m.config
    friction = str(_config_get(c, "allocation.friction", "pyramid4"))
    solver = str(_config_get(c, "allocation.solver", "auto"))
    if solver == "auto":
        solver = "ipopt" if friction == "cone" else "active-set"
    return {"grid": str(_config_get(c, "output.grid", "adaptive")),
            "sample_step": parse_number(_config_get(c, "output.sample_step", math.nan)),
            "event_step": parse_number(_config_get(c, "output.event_step", math.nan)),
            "impact_samples": int(parse_number(_config_get(c, "output.impact_samples", -1))),
            "tolerance": parse_number(_config_get(c, "allocation.tolerance", math.nan)),
            "solver": solver, "friction": friction,
            "leg_inertia": str(_config_get(c, "robot.leg_inertia", "full")),
            "contact_model": str(_config_get(c, "contact.model", "compliant"))}


COLUMNS = (  # name, units, kind
    ("label", "1", "str"), ("category", "1", "str"), ("reference", "1", "str"),
    ("overrides", "1", "str"), ("grid", "1", "str"), ("sample_step", "s", "f8"),
    ("event_step", "s", "f8"), ("impact_samples", "1", "i4"), ("tolerance", "1", "f8"),
    ("solver", "1", "str"), ("friction", "1", "str"), ("leg_inertia", "1", "str"),
    ("contact_model", "1", "str"), ("samples", "1", "i4"), ("relaxed_samples", "1", "i4"),
    ("failed_samples", "1", "i4"), ("repeats", "1", "i4"), ("wall_time_s", "s", "f8"),
    ("energy_J", "J", "f8"), ("tau_peak_Nm", "N m", "f8"), ("tau_rms_Nm", "N m", "f8"),
    ("err_peak", "1", "f8"), ("err_impulse", "1", "f8"), ("err_energy", "1", "f8"),
    ("err_tau_peak", "1", "f8"), ("err_tau_rms", "1", "f8"), ("impacts_match", "1", "i1"),
    ("is_default", "1", "i1"),
)


def write_study(path, meta, rows, references, verdict):
    """Writes the study file atomically (temporary name in the same directory)."""
    directory = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=f".{os.path.basename(path)}.", suffix=".tmp", dir=directory)
    os.close(fd)
    try:
        with h5py.File(tmp, "w") as f:
            g = f.create_group("meta")
            for k, v in meta.items():
                g.attrs[k] = v
            runs = f.create_group("runs")
            for name, units, kind in COLUMNS:
                values = [r[name] for r in rows]
                if kind == "str":
                    ds = runs.create_dataset(name, data=np.array(values, dtype=object),
                                             dtype=h5py.string_dtype())
                else:
                    ds = runs.create_dataset(name, data=np.array(values, dtype=kind))
                ds.attrs["units"] = units
            refs = f.create_group("references")
            for name, (attrs, datasets) in references.items():
                rg = refs.create_group(name)
                for k, v in attrs.items():
                    rg.attrs[k] = v
                for k, (units, v) in datasets.items():
                    rg.create_dataset(k, data=v).attrs["units"] = units
            vg = f.create_group("verdict")
            for k, v in verdict.items():
                vg.attrs[k] = v
        with open(tmp, "rb") as fh:
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise


# ---------------------------------------------------------------- main


def check_output_path(path):
    directory = os.path.dirname(os.path.abspath(path))
    try:
        os.makedirs(directory, exist_ok=True)
    except OSError as e:
        raise StudyError(f"cannot create the output directory {directory}: {e.strerror}")
    if not os.access(directory, os.W_OK):
        raise StudyError(f"output directory {directory} is not writable")
    if os.path.isdir(path):
        raise StudyError(f"output {path} is a directory")


def find_hexdyn(arg):
    path = arg or os.path.join(os.environ.get("HEXDYN_BUILD", os.path.join(ROOT, "build")),
                               "hexdyn")
    if not os.path.isfile(path) or not os.access(path, os.X_OK):
        raise StudyError(f"hexdyn binary not found or not executable: {path} (build it: "
                         f"cmake -S . -B build -DCMAKE_BUILD_TYPE=Release && cmake --build build, "
                         f"or pass --hexdyn)")
    return path


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("study", nargs="?", default=DEFAULT_STUDY, help="study file (YAML)")
    ap.add_argument("-o", "--output", default=DEFAULT_OUTPUT, help="study file to write (HDF5)")
    ap.add_argument("--hexdyn", help="hexdyn binary (default $HEXDYN_BUILD/hexdyn or build/hexdyn)")
    ap.add_argument("--keep-runs", metavar="DIR", help="also keep every run's result file in DIR")
    ap.add_argument("-q", "--quiet", action="store_true", help="no progress lines")
    args = ap.parse_args(argv)
    started = time.monotonic()

    study = load_study(args.study)
    hexdyn_src = find_hexdyn(args.hexdyn)
    if not os.path.isfile(study["scene"]):
        raise StudyError(f"{args.study}: scene: no such file {study['scene']}")
    with open(study["scene"], encoding="utf-8") as f:
        scene_text = f.read()
    try:
        scene = yaml.safe_load(scene_text) or {}
    except yaml.YAMLError as e:
        raise StudyError(f"{study['scene']}: not valid YAML: {str(e).splitlines()[0]}")

    with tempfile.TemporaryDirectory(prefix="hexdyn-study-") as workdir:
        hexdyn = os.path.join(workdir, "hexdyn")
        shutil.copy2(hexdyn_src, hexdyn)  # one build for the whole study
        version = subprocess.run([hexdyn, "--version"], capture_output=True, text=True)
        version = version.stdout.strip() or version.stderr.strip()

        # Distinct runs, references first.
        specs = {}

        def spec_of(sets, name, where):
            s = RunSpec(sets, scene)
            if s.key not in specs:
                s.name = name
                validate_run(hexdyn, study["scene"], s, where)
                specs[s.key] = s
            return specs[s.key]

        used_refs = {CONVERGED} | {s["reference"] for s in study["series"]}
        ref_specs, check_specs = {}, {}
        for name in study["references"]:
            if name not in used_refs:
                continue
            r = study["references"][name]
            where = f"{args.study}: references.{name}"
            ref_specs[name] = spec_of(r["set"], f"reference {name}", where)
            if r["check"] is not None:
                sets = dict(r["set"])
                sets.update(r["check"])
                check_specs[name] = spec_of(sets, f"reference {name} check", where + ".check")
        rows = [{"label": DEFAULT_LABEL, "category": DEFAULT_LABEL, "reference": CONVERGED,
                 "spec": spec_of({}, DEFAULT_LABEL, f"{args.study}: default")}]
        for name, s in ref_specs.items():
            rows.append({"label": f"reference {name}", "category": "reference",
                         "reference": name, "spec": s})
            if name in check_specs:
                rows.append({"label": f"reference {name} check", "category": "reference",
                             "reference": name, "spec": check_specs[name]})
        for i, s in enumerate(study["series"]):
            for r in s["runs"]:
                where = f"{args.study}: series[{i}] ({s['category']}) '{r['label']}'"
                rows.append({"label": f"{s['category']} {r['label']}", "category": s["category"],
                             "reference": s["reference"],
                             "spec": spec_of(r["set"], f"{s['category']} {r['label']}", where)})
        check_output_path(args.output)  # after every check of the input, before any run
        if args.keep_runs:
            os.makedirs(args.keep_runs, exist_ok=True)
        log(f"{len(specs)} distinct runs, {len(rows)} rows, scene {study['scene']}, {version}",
            args.quiet)

        counter = [0]
        first = list(dict.fromkeys(ref_specs.values()))  # the references, run first
        order = first + [s for s in specs.values() if s not in first]

        def measure_against_references(s):
            for name, rs in ref_specs.items():
                s.result.windows[name] = s.result.sample_windows(rs.result)
            s.result.matches = {name: s.result.impacts_match(rs.result)
                                for name, rs in ref_specs.items()}

        for i, s in enumerate(order):
            s.result = execute(s, hexdyn, study["scene"], workdir, study["repeats"],
                               args.keep_runs, args.quiet, counter, f"[{i + 1}/{len(order)}] ")
            if i + 1 == len(first):  # every reference done: measure them against each other
                for r in first:
                    measure_against_references(r)
                for r in first:
                    r.result.drop_arrays()
            elif i >= len(first):
                measure_against_references(s)
                s.result.drop_arrays()

        pairs = study["repeats"]["paired"]
        paired_walls = None
        if pairs:
            log(f"cost of the verdict: default and reference {CONVERGED}, alternating, "
                f"{pairs} runs each", args.quiet)
            default_spec = rows[0]["spec"]
            paired_walls = timed_runs([default_spec, ref_specs[CONVERGED]], hexdyn,
                                      study["scene"], workdir, pairs, counter)

    out_rows = []
    for r in rows:
        m = r["spec"].result
        ref = ref_specs[r["reference"]].result
        row = {"label": r["label"], "category": r["category"], "reference": r["reference"],
               "overrides": r["spec"].overrides, "samples": m.samples,
               "relaxed_samples": m.relaxed, "failed_samples": m.failed,
               "repeats": len(m.wall_times), "wall_time_s": m.wall_time_s,
               "energy_J": m.energy, "tau_peak_Nm": m.tau_peak, "tau_rms_Nm": m.tau_rms,
               "impacts_match": m.matches[r["reference"]],
               "is_default": int(r["label"] == DEFAULT_LABEL)}
        row.update(describe(m))
        row.update(errors(m, r["reference"], ref))
        if row["impacts_match"] == 0:
            log(f"warning: '{r['label']}': its /impacts differ from reference "
                f"{r['reference']}'s touchdowns", args.quiet)
        out_rows.append(row)

    references = {}
    for name, s in ref_specs.items():
        m = s.result
        peaks, impulses = m.windows[name]
        attrs = {"overrides": s.overrides, "samples": m.samples, "wall_time_s": m.wall_time_s,
                 "repeats": len(m.wall_times), "energy_J": m.energy,
                 "tau_peak_Nm": m.tau_peak, "tau_rms_Nm": m.tau_rms}
        if name in check_specs:
            c = check_specs[name]
            attrs.update({"check_overrides": c.overrides, "check_samples": c.result.samples,
                          "check_wall_time_s": c.result.wall_time_s})
            for k, v in errors(c.result, name, m).items():
                attrs[f"floor_{k}"] = v
        datasets = {"impact_leg": ("1", m.impact_leg.astype(np.int32)),
                    "impact_t_start": ("s", m.impact_t0),
                    "impact_duration": ("s", m.impact_duration),
                    "sampled_peak_N": ("N", peaks), "sampled_impulse_Ns": ("N s", impulses)}
        references[name] = (attrs, datasets)

    default = out_rows[0]
    ref = ref_specs[CONVERGED].result
    t = study["targets"]
    default_wall, ref_wall = paired_walls or (default["wall_time_s"], ref.wall_time_s)
    cost_ratio = default_wall / ref_wall
    verdict = {"label": DEFAULT_LABEL, "reference": CONVERGED,
               "err_peak": default["err_peak"], "err_energy": default["err_energy"],
               "wall_time_s": default_wall, "reference_wall_time_s": ref_wall,
               "cost_ratio": cost_ratio, "cost_pairs": np.int32(pairs),
               "samples": default["samples"],
               "reference_samples": ref.samples,
               "samples_ratio": default["samples"] / ref.samples,
               "target_peak": t["peak"], "target_energy": t["energy"], "target_cost": t["cost"],
               "pass_peak": np.int8(default["err_peak"] <= t["peak"]),
               "pass_energy": np.int8(default["err_energy"] <= t["energy"]),
               "pass_cost": np.int8(cost_ratio <= t["cost"])}
    verdict["pass_all"] = np.int8(verdict["pass_peak"] and verdict["pass_energy"]
                                  and verdict["pass_cost"])

    meta = {"schema": STUDY_SCHEMA, "schema_version": np.int64(STUDY_SCHEMA_VERSION),
            "created_utc": datetime.datetime.now(datetime.timezone.utc).strftime(
                "%Y-%m-%dT%H:%M:%SZ"),
            "hexdyn_version": ref.version, "git_commit": ref.git_commit,
            "study_file": os.path.relpath(os.path.abspath(args.study), ROOT),
            "study_yaml": study["text"],
            "scene_file": os.path.relpath(study["scene"], ROOT), "scene_yaml": scene_text,
            "hexdyn_processes": np.int64(counter[0]),
            "study_wall_time_s": time.monotonic() - started}
    write_study(args.output, meta, out_rows, references, verdict)

    def word(ok):
        return "PASS" if ok else "FAIL"

    floor = references[CONVERGED][0]
    print(f"study: wrote {args.output} ({len(out_rows)} rows, {counter[0]} hexdyn runs, "
          f"{meta['study_wall_time_s']:.0f} s)")
    if "floor_err_energy" in floor:
        print("reference floor (check run vs reference): " + ", ".join(
            f"{k[4:]} {floor['floor_' + k]:.2e}" for k in ERROR_METRICS))
    print(f"adaptive grid (default) vs converged reference: "
          f"peak {verdict['err_peak']:.2e} <= {t['peak']:g}: {word(verdict['pass_peak'])}; "
          f"energy {verdict['err_energy']:.2e} <= {t['energy']:g}: "
          f"{word(verdict['pass_energy'])}; cost {default_wall:.4g} s / "
          f"{ref_wall:.4g} s = {cost_ratio:.1%} <= {t['cost']:.0%}: "
          f"{word(verdict['pass_cost'])} (samples {default['samples']}/{ref.samples} = "
          f"{verdict['samples_ratio']:.1%})")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except StudyError as e:
        print(f"study: error: {e}", file=sys.stderr)
        sys.exit(e.status)
    except KeyboardInterrupt:
        print("study: interrupted, nothing written", file=sys.stderr)
        sys.exit(130)
