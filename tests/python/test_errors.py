"""hexdyn's errors in Python: each bad input raises the class of the C++ family that the CLI
reports with the same exit status, with the CLI's message (its line without "hexdyn: error: ");
ConfigError is a ValueError and IoError an OSError; Result.write refuses what `hexdyn run -o`
refuses; no input crashes the interpreter or lets another exception through. The readers
refuse a file whose datasets are off the schema (copies of real files corrupted with h5py)
with hexdyn.IoError in one line naming the file and the dataset; every function taking a
path refuses one with a NUL character with ValueError before anything reads the path.
    test_errors.py HEXDYN_BINARY SOURCE_DIR"""

import os
import pathlib
import shutil
import signal
import socket
import subprocess
import tempfile

import h5py
import numpy as np

import hexdyn
from common import args, cli_error
from hexdyn import results as hr
from hexdyn import xr as hx

HEXDYN, SRC = args()
PAPER = os.path.join(SRC, "configs/paper.yaml")

assert issubclass(hexdyn.ConfigError, hexdyn.Error) and issubclass(hexdyn.ConfigError, ValueError)
assert issubclass(hexdyn.IoError, hexdyn.Error) and issubclass(hexdyn.IoError, OSError)
for name in ("ReachError", "PlanningError", "SolverError", "InternalError"):
    assert issubclass(getattr(hexdyn, name), hexdyn.Error), name


def raises(cls, f, *a, **k):
    try:
        f(*a, **k)
    except cls as e:
        return str(e)
    except BaseException as e:  # noqa: B036 (what else came through is the failure)
        raise AssertionError(f"expected {cls.__name__}, got {type(e).__name__}: {e}")
    raise AssertionError(f"expected {cls.__name__}, nothing raised")


with tempfile.TemporaryDirectory() as d:
    # Same error, same message as the CLI: (CLI argv, Python call, class).
    cases = [
        (["validate", f"{d}/missing.yaml"], lambda: hexdyn.validate(f"{d}/missing.yaml"), hexdyn.ConfigError, 2),
        (["validate", d], lambda: hexdyn.validate(d), hexdyn.ConfigError, 2),
        (["validate", PAPER, "--set", "gait.duty_factor=7"],
         lambda: hexdyn.validate(PAPER, set={"gait.duty_factor": 7}), hexdyn.ConfigError, 2),
        (["run", PAPER, "-o", f"{d}/x.h5", "--set", "gait.nonsense=1"],
         lambda: hexdyn.run(PAPER, set={"gait.nonsense": 1}), hexdyn.ConfigError, 2),
        (["run", PAPER, "-o", f"{d}/x.h5", "--set", "terrain.riser_height=0.3"],
         lambda: hexdyn.run(PAPER, set={"terrain.riser_height": 0.3}), hexdyn.Error, 3),
    ]
    for argv, call, cls, status in cases:
        rc, want = cli_error(HEXDYN, argv)
        assert rc == status, (argv, rc)
        got = raises(cls, call)
        assert got == want, f"{argv}:\n  python: {got}\n  cli:    {want}"
        if status == 3:
            assert not isinstance(got, ValueError)
    # The same checks on an output path as `hexdyn run -o`.
    r = hexdyn.run(PAPER)
    for target in (PAPER, d, f"{d}/no/such/folder/x.h5", "/proc/x.h5"):
        rc, want = cli_error(HEXDYN, ["run", PAPER, "-o", target])
        got = raises(hexdyn.IoError, r.write, target)
        assert got == want, f"write {target}:\n  python: {got}\n  cli:    {want}"
    # Nonsense from Python is a TypeError or a hexdyn error, never a crash.
    raises(TypeError, hexdyn.run, PAPER, set=["gait.duty_factor"])
    raises(TypeError, hexdyn.run, PAPER, set={"gait.duty_factor": object()})
    raises(TypeError, hexdyn.run, None)
    raises(hexdyn.ConfigError, hexdyn.run, PAPER, set={"gait": {"duty_factor": [1, {"a": None}]}})
    raises(hexdyn.ConfigError, hexdyn.run, PAPER, set={"": 1})
    raises(hexdyn.ConfigError, hexdyn.run, "")
    with open(f"{d}/bad.yaml", "w") as f:
        f.write("gait: [1, 2\n")
    raises(hexdyn.ConfigError, hexdyn.run, f"{d}/bad.yaml")
    v = hexdyn.validate(os.path.join(SRC, "configs/sweeps/smoke.yaml"))
    assert v["kind"] == "sweep" and v["scenarios"] > 0, v
    # The report's messages are the lines `hexdyn validate` prints, for a sweep and a scene.
    for path in (os.path.join(SRC, "configs/sweeps/smoke.yaml"), PAPER):
        cli = subprocess.run([HEXDYN, "validate", path], capture_output=True, text=True, check=True)
        assert hexdyn.validate(path)["messages"] == cli.stdout.splitlines(), (path, cli.stdout)
    # The readers refuse anything but a regular file before opening it, with one line: a FIFO
    # (opened for reading it would wait for a writer for ever: an alarm fails the test instead
    # of hanging it), a directory, a device, a socket. A link to a result file opens.
    r.write(f"{d}/r.h5")
    os.symlink(f"{d}/r.h5", f"{d}/link.h5")
    assert hexdyn.open_result(f"{d}/link.h5").meta["schema"] == "hexdyn-result/5"
    os.mkfifo(f"{d}/fifo.h5")
    server = socket.socket(socket.AF_UNIX)
    server.bind(f"{d}/socket.h5")
    from hexdyn.xr import open_envelope
    signal.signal(signal.SIGALRM, lambda *_: (_ for _ in ()).throw(AssertionError("reader hung")))
    for target, kind in ((f"{d}/fifo.h5", "a FIFO"), (d, "a directory"), ("/dev/null", "a device"),
                         (f"{d}/socket.h5", "a socket")):
        for reader in (hexdyn.open_result, hexdyn.open_sweep, open_envelope):
            signal.alarm(10)
            got = raises(hexdyn.IoError, reader, target)
            signal.alarm(0)
            assert got == f"{target}: is {kind}, not a regular file", (reader.__name__, got)
            assert "\n" not in got
    server.close()
    got = raises(hexdyn.IoError, hexdyn.open_result, f"{d}/missing.h5")
    assert got.startswith(f"{d}/missing.h5: cannot be read"), got


def cli(*argv):
    subprocess.run([HEXDYN, *argv], check=True, stderr=subprocess.DEVNULL,
                   env=dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
                            OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1"))


def corrupt(src, dst, path, new):
    """A copy of the file `src` at `dst` with the dataset `path` replaced by new(its values)."""
    shutil.copy(src, dst)
    with h5py.File(dst, "r+") as f:
        old = f[path][()]
        del f[path]
        if new is not None:
            f[path] = new(old)


def shape(path, dataset):
    with h5py.File(path, "r") as f:
        return f[dataset].shape


ENVELOPE_AXES = ("tread_depth", "duty_factor", "peak_speed", "criteria")


def strings(values):
    return np.array([str(v) for v in np.ravel(values)], dtype=h5py.string_dtype())


with tempfile.TemporaryDirectory() as d:
    # Real files of the current writer, which open, and copies with one dataset off the schema,
    # which do not: hexdyn.IoError, one line "FILE: dataset PATH is FOUND, expected ...", naming
    # what was found and what the schema expects (the sizes from the untouched datasets); a
    # /time cut short names /time as what fixed T.
    result, sweep, envelope, cases = (f"{d}/{n}.h5" for n in ("r", "s", "e", "c"))
    cli("run", PAPER, "-o", result)
    cli("sweep", os.path.join(SRC, "configs/sweeps/smoke.yaml"), "-o", sweep, "--keep-runs")
    cli("envelope", os.path.join(SRC, "tests/data/envelope_quick.yaml"), "-o", envelope)
    cli("envelope", os.path.join(SRC, "tests/data/envelope_cases.yaml"), "-o", cases)
    hexdyn.open_result(result), hexdyn.open_sweep(sweep).run(1)
    hx.open_envelope(envelope), hx.open_envelope(cases)
    T, = shape(result, "time")
    N, = shape(sweep, "scenarios/id")
    L, J = shape(result, "model/leg_names")[0], shape(result, "model/joint_names")[0]
    W, B, S, C = (shape(envelope, f"axes/{a}")[0] for a in ENVELOPE_AXES)
    cells = tuple(shape(cases, f"axes/{a}")[0] for a in ("case",) + ENVELOPE_AXES)
    # (file, dataset, new values, reader, the dataset named, what else the message says)
    broken = [
        (result, "time", strings, hexdyn.open_result, "/time", ["string", "float64"]),
        (result, "time", lambda v: v[:10], hexdyn.open_result, "/time",
         ["T = 10 from /time", f"({T}, ", "(10, "]),
        (result, "time", None, hexdyn.open_result, "/time", ["no dataset"]),
        (result, "joints/torque", lambda v: v[:, :-1], hexdyn.open_result, "/joints/torque",
         [f"({T}, {J - 1})", f"({T}, {J})"]),
        (result, "feet/position", lambda v: v[:, :, :2], hexdyn.open_result, "/feet/position",
         [f"({T}, {L}, 2)", f"({T}, {L}, 3)"]),
        (result, "contacts/phase", lambda v: v.astype(np.float64), hexdyn.open_result,
         "/contacts/phase", [f"float64 ({T}, {L})", f"int8 ({T}, {L})"]),
        (result, "impacts/leg", lambda v: v.astype(np.float64), hexdyn.open_result, "/impacts/leg",
         ["is float64", "expected int32"]),
        (result, "energy/total", lambda v: np.array([v]), hexdyn.open_result, "/energy/total",
         ["(1,)", "()"]),
        (sweep, "scenarios/energy", lambda v: v[:N - 3], hexdyn.open_sweep, "/scenarios/energy",
         [f"({N - 3},)", f"({N},)"]),
        (sweep, "scenarios/peak_torque", lambda v: v[:, :-1], hexdyn.open_sweep,
         "/scenarios/peak_torque", [f"({N}, {J - 1})", f"({N}, {J})"]),
        (sweep, "scenarios/status", lambda v: v.astype(np.float64), hexdyn.open_sweep,
         "/scenarios/status", ["float64", "int8"]),
        (sweep, "axes/0/labels", lambda v: v[:1], hexdyn.open_sweep, "/axes/0/labels", ["(1,)"]),
        (sweep, "runs/000001/time", lambda v: v[:10], lambda p: hexdyn.open_sweep(p).run(1),
         "/time", [":/runs/000001: ", "T = 10 from /time"]),
        (envelope, "envelope/riser_max", lambda v: v.reshape(-1), hx.open_envelope,
         "/envelope/riser_max", [f"({W * B * S * C},)", f"({W}, {B}, {S}, {C})"]),
        (envelope, "envelope/limit", strings, hx.open_envelope,  # flattened
         "/envelope/limit", [f"string ({W * B * S * C},)", f"string ({W}, {B}, {S}, {C})"]),
        (envelope, "envelope/posture_height", lambda v: v[..., None], hx.open_envelope,
         "/envelope/posture_height", [f"({W}, {B}, {S})"]),
        (envelope, "probes/passed", lambda v: v.astype(np.int32), hx.open_envelope,
         "/probes/passed", ["int32", "int8"]),
        (cases, "envelope/riser_fail", lambda v: v[0], hx.open_envelope, "/envelope/riser_fail",
         [str(cells[1:]), str(cells)]),
    ]
    for k, (src, dataset, new, reader, named, says) in enumerate(broken):
        bad = f"{d}/bad{k}.h5"
        corrupt(src, bad, dataset, new)
        got = raises(hexdyn.IoError, reader, bad)
        assert "\n" not in got and got.startswith(f"{bad}:"), (dataset, got)
        assert any(f"{w} {named}{c}" in got for w, c in (("dataset", " "), ("dataset", ","),
                                                          ("from", ")"))), (dataset, got)
        assert all(w in got for w in says), (dataset, says, got)
    # Not HDF5, or cut short: one line, hexdyn.IoError.
    with open(f"{d}/text.h5", "w") as f:
        f.write("not HDF5\n")
    shutil.copy(result, f"{d}/short.h5")
    os.truncate(f"{d}/short.h5", os.path.getsize(result) // 2)
    for bad in (f"{d}/text.h5", f"{d}/short.h5"):
        for reader in (hexdyn.open_result, hexdyn.open_sweep, hx.open_envelope):
            got = raises(hexdyn.IoError, reader, bad)
            assert got.startswith(f"{bad}: ") and "\n" not in got, got

    # A NUL in a path: ValueError in one line from every function taking a path, before the
    # C++ side or the OS (which stop at the NUL: "paper.yaml\0junk" ran paper.yaml).
    r = hexdyn.run(pathlib.Path(PAPER))
    assert hexdyn.validate(pathlib.Path(PAPER))["kind"] == "scene"

    class Named:  # an os.PathLike
        def __init__(self, p):
            self.p = p

        def __fspath__(self):
            return self.p

    read = hexdyn.open_result(result)
    calls = [hexdyn.run, hexdyn.validate, r.write, read.write, hexdyn.open_result,
             hexdyn.open_sweep, hexdyn.open_envelope, hexdyn.open_study, hexdyn.check_layout,
             hx.open_envelope, hr.check_regular_file, hr.open_h5]
    for target in (f"{PAPER}\0junk", f"{result}\0", os.fsencode(result) + b"\0x",
                   Named(f"{d}/w.h5\0junk"), f"{d}/w.h5\0junk"):
        for call in calls:
            got = raises(ValueError, call, target)
            assert "NUL" in got and "\n" not in got, (call, got)
    assert not os.path.exists(f"{d}/w.h5")
print("python errors: ok")
