"""Publishing a file atomically from Python, as hexdyn's compiled writers do
(src/hexdyn/process/atomic_file.hpp; docs/user/faults.md#pythons-writer): the file is built
under a temporary name beside its final path, synced to disk and renamed over that path only
when complete, so that a reader sees the old file or the new one, never part of one.

    publish_atomically("copy.h5", produce)   # produce(check) -> the file's bytes

- The bytes are made in memory (Result.write of a read result: an HDF5 image, h5py's core
  driver) and written with write(2): HDF5 never meets the disk, so a full disk is the OS's
  ENOSPC in one line, never a crash inside HDF5 that leaves a file behind.
- The temporary name is `.NAME.tmp.PID.RANDOM`, cut to the folder's NAME_MAX (the name's
  start and a digest of the whole name) so that every valid output name can be written.
- In the main thread, the signals that would end Python (SIGHUP, SIGQUIT, SIGTERM, SIGUSR1,
  SIGUSR2, SIGALRM, SIGPIPE and SIGINT while their action is the default; SIGINT also while
  Python's own handler, KeyboardInterrupt, has it) are recorded while the file is written;
  the writer looks between steps (each member of the root copied, every CHUNK bytes
  written), removes the temporary file, restores the handlers and ends the process with one
  line and exit status 128 + signal, as `hexdyn run` and the computed result's writer do
  (SIGINT under Python's handler raises KeyboardInterrupt with that line instead). A signal
  the program handles itself is left to it. Other threads install nothing: Python sets
  handlers in the main thread only.

Needs nothing but the standard library (the readers work without the compiled part).
"""

import hashlib
import os
import secrets
import signal
import stat
import sys
import threading

# The signals whose default action ends the process and that are sent as requests: those of
# src/hexdyn/process/interrupt.hpp (kHandled).
HANDLED_SIGNALS = (signal.SIGHUP, signal.SIGINT, signal.SIGQUIT, signal.SIGTERM, signal.SIGUSR1,
                   signal.SIGUSR2, signal.SIGALRM, signal.SIGPIPE)

CHUNK = 8 << 20  # bytes per write(2); a signal is looked at after each


def _io_error(message):
    """hexdyn.IoError (an OSError) when the compiled part is there, else OSError."""
    from .h5files import io_error as make
    return make(message)


def output_error(name, reason):
    """The error of an output path refused before anything is written."""
    return _io_error(f"cannot write output '{name}': {reason}")


def temporary_path_for(name):
    """The temporary path of the output `name` while it is written: `.BASE.tmp.PID.RANDOM`
    beside it (RANDOM: 12 hex digits, so that no two writes share it). When that name would
    pass the folder's NAME_MAX (255 bytes on Linux file systems), BASE is cut at a UTF-8
    character boundary and followed by "~" and 16 hex digits of the SHA-256 of the whole
    BASE: any name the folder admits has a temporary name it admits too."""
    folder, base = os.path.split(name)
    try:
        limit = os.pathconf(folder or ".", "PC_NAME_MAX")
    except (OSError, ValueError):
        limit = None
    limit = limit if limit and limit > 0 else 255
    raw = os.fsencode(base)
    tail = f".tmp.{os.getpid()}.{secrets.token_hex(6)}".encode()
    if 1 + len(raw) + len(tail) > limit:
        digest = b"~" + hashlib.sha256(raw).hexdigest()[:16].encode()
        keep = max(0, limit - 1 - len(tail) - len(digest))
        raw = raw[:keep].decode("utf-8", "ignore").encode("utf-8") + digest
    tmp = os.fsdecode(b"." + raw + tail)
    return os.path.join(folder, tmp) if folder else tmp


def why_not_replaceable(name):
    """Why an existing `name` must not be replaced (src/hexdyn/process/atomic_file.hpp: only a
    regular file is, never a link, a folder or a special file), or None: also when lstat(2)
    fails (no such file; another reason is the OS's to give when the file is written)."""
    try:
        mode = os.lstat(name).st_mode
    except OSError:
        return None
    if stat.S_ISREG(mode):
        return None
    if stat.S_ISLNK(mode):
        return "is a symbolic link (hexdyn replaces only regular files; name the link's target)"
    return ("is a directory" if stat.S_ISDIR(mode) else
            "is a character device" if stat.S_ISCHR(mode) else
            "is a block device" if stat.S_ISBLK(mode) else
            "is a FIFO (named pipe)" if stat.S_ISFIFO(mode) else
            "is a socket" if stat.S_ISSOCK(mode) else "is not a regular file")


class _Interrupted(BaseException):
    """A recorded signal seen by SignalWatch.check: stops the write (never leaves this file)."""


class SignalWatch:
    """Records the handled signals that would end Python while a file is written (see the
    module's note). install() in the main thread only; restore() puts the handlers back
    (signal.signal runs any handler still pending first, so a signal that came just before is
    recorded, not lost); check() raises _Interrupted once one was recorded."""

    def __init__(self):
        self.received = 0
        self.keyboard_interrupt = False  # SIGINT was Python's (KeyboardInterrupt)
        self._old = {}

    def _record(self, sig, frame):
        if not self.received:
            self.received = sig
            self.keyboard_interrupt = self._old.get(sig) is signal.default_int_handler

    def install(self):
        if threading.current_thread() is not threading.main_thread():
            return
        for sig in HANDLED_SIGNALS:
            old = signal.getsignal(sig)
            if old == signal.SIG_DFL or (sig == signal.SIGINT
                                         and old is signal.default_int_handler):
                self._old[sig] = old
                signal.signal(sig, self._record)

    def restore(self):
        """The handlers as they were. A pending handler of the program's own that raises is
        re-raised once every handler is back."""
        raised = None
        while self._old:
            sig, old = next(iter(self._old.items()))
            try:
                signal.signal(sig, old)
                del self._old[sig]
            except BaseException as e:  # noqa: B036 (a handler of the program's, run first)
                raised = raised or e
        if raised is not None:
            raise raised

    def check(self):
        if self.received:
            raise _Interrupted()


def _end_process(sig, line):
    """Writes `line` on stderr and ends the process with 128 + sig, as the compiled writer's
    handler does (the default action of the signal would have ended it)."""
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError, AttributeError):
            pass
    data = (line + "\n").encode("utf-8", "replace")
    try:
        while data:
            data = data[os.write(2, data):]
    except OSError:
        pass
    os._exit(128 + sig)


def _write_all(fd, data, check):
    view = memoryview(data)
    for start in range(0, len(view), CHUNK):
        part = view[start:start + CHUNK]
        while part:
            part = part[os.write(fd, part):]
        check()


def _create(name):
    """(temporary path, descriptor) of a new temporary file for `name`: created as hexdyn's
    writers create files (mode 0666 less the umask), never through a link."""
    tmp = temporary_path_for(name)
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC
    try:
        return tmp, os.open(tmp, flags, 0o666)
    except OSError as e:
        raise output_error(name, e.strerror) from None


class _Failed:
    """A context in which an OSError, ValueError or KeyError (the OS's, HDF5's through h5py) is
    hexdyn.IoError "cannot write 'NAME': REASON" in one line, the OS's reason when it gave one
    ("No space left on device")."""

    def __init__(self, name):
        self.name = name

    def __enter__(self):
        return self

    def __exit__(self, kind, error, trace):
        if kind is None or not issubclass(kind, (OSError, ValueError, KeyError)):
            return False
        if isinstance(error, OSError) and error.strerror:
            reason = error.strerror
        else:
            text = str(error).strip()
            reason = text.splitlines()[0] if text else kind.__name__
        raise _io_error(f"cannot write '{self.name}': {reason}") from None


def _build(name, tmp, fd, produce, watch):
    """produce's bytes into the temporary file, synced, then renamed over `name`. Returns
    True once renamed."""
    with _Failed(name):
        try:
            data = produce(watch.check)
            watch.check()
            _write_all(fd, data, watch.check)
            del data
            os.fsync(fd)
        finally:
            os.close(fd)
    watch.check()
    why = why_not_replaceable(name)  # a link or a special file put there meanwhile
    if why:
        raise output_error(name, f"it {why}")
    with _Failed(name):
        os.replace(tmp, name)
    return True


def publish_atomically(path, produce):
    """Writes the file `path` atomically: produce(check) returns its bytes (calling check()
    now and then: it stops the write once a signal came), written to a temporary file beside
    `path`, synced and renamed over `path`. Any error removes the temporary file and leaves an
    existing file at `path` as it was: hexdyn.IoError in one line naming `path` (with the OS's
    reason: "cannot write 'X': No space left on device"); a signal ends the process (see the
    module's note). The folder of `path` must exist; `path` must be no link nor special file
    (checked again right before the rename)."""
    name = os.fsdecode(path)
    watch = SignalWatch()
    tmp, published, error = None, False, None
    try:
        watch.install()
        tmp, fd = _create(name)
        published = _build(name, tmp, fd, produce, watch)
    except _Interrupted:
        pass
    except BaseException as e:  # noqa: B036 (raised again once cleaned up)
        error = e
    finally:
        if tmp is not None and not published:
            try:
                os.remove(tmp)
            except OSError:
                pass
        watch.restore()
    if watch.received:
        _report_signal(watch, name, published)
    if error is not None:
        raise error


def _report_signal(watch, name, published):
    """The line of a signal recorded during the write, and the end it asks for."""
    from .h5files import one_line as _one_line
    sig, name = watch.received, _one_line(name)
    signame = signal.Signals(sig).name
    if published:
        line = f"write: {signame} arrived after {name} was complete; it is kept"
    else:
        line = (f"write interrupted by {signame}: nothing written to {name} (an existing file "
                "there is kept, no temporary file left)")
    if watch.keyboard_interrupt:
        raise KeyboardInterrupt(line)
    _end_process(sig, "hexdyn: " + line)
