"""hexdyn's errors in Python: each bad input raises the class of the C++ family that the CLI
reports with the same exit status, with the CLI's message (its line without "hexdyn: error: ");
ConfigError is a ValueError and IoError an OSError; Result.write refuses what `hexdyn run -o`
refuses; no input crashes the interpreter or lets another exception through.
    test_errors.py HEXDYN_BINARY SOURCE_DIR"""

import os
import signal
import socket
import tempfile

import hexdyn
from common import args, cli_error

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
    # The readers refuse anything but a regular file before opening it, with one line: a FIFO
    # (opened for reading it would wait for a writer for ever: an alarm fails the test instead
    # of hanging it), a directory, a device, a socket. A link to a result file opens.
    r.write(f"{d}/r.h5")
    os.symlink(f"{d}/r.h5", f"{d}/link.h5")
    assert hexdyn.open_result(f"{d}/link.h5").meta["schema"] == "hexdyn-result/2"
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
print("python errors: ok")
