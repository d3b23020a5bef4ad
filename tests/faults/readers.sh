#!/bin/bash
# Readers: Python's open_result, open_sweep and open_envelope given a
# FIFO, a directory or /dev/zero, or a result, sweep or envelope file with a dataset off the
# schema (rewritten with h5py), a file that is not HDF5 or one cut short: each gives one line
# of hexdyn's error (hexdyn.IoError) within 10 s, never a hang or a traceback, and the file
# read is left byte for byte as it was. The readers run under a small `python -c` wrapper
# that prints hexdyn's error as the CLI does ("hexdyn: error: MESSAGE") and exits with 2.
# shellcheck source=common.sh
source "$(dirname "$0")/common.sh"
# The package hexdyn of the build tree, unless the caller (ctest) names one.
export PYTHONPATH="${PYTHONPATH:-$(dirname "$HEXDYN")/python}"

"$HEXDYN" run "$PAPER" -o r.h5 2> run.log || fail "run: $(cat run.log)"
"$HEXDYN" sweep "$SMOKE" -o s.h5 > sweep.log 2>&1 || fail "sweep: $(cat sweep.log)"
"$HEXDYN" envelope "$SRC/tests/data/envelope_quick.yaml" -o e.h5 2> envelope.log ||
  fail "envelope: $(cat envelope.log)"

# read_with READER FILE LOG: READER (open_result, open_sweep or open_envelope) on FILE under
# `timeout 10`; stderr to LOG; the wrapper's exit status (124: the reader hung).
read_with() {
  timeout 10 "$PY" -c '
import sys
import hexdyn
from hexdyn import xr
reader = {"open_result": hexdyn.open_result, "open_sweep": hexdyn.open_sweep,
          "open_envelope": xr.open_envelope}[sys.argv[1]]
try:
    reader(sys.argv[2])
except hexdyn.Error as e:
    print(f"hexdyn: error: {e}", file=sys.stderr)
    sys.exit(2)
' "$1" "$2" > /dev/null 2> "$3"
}

# refused READER FILE PATTERN: READER on FILE gives one line of hexdyn's error matching
# PATTERN, exit status 2, no traceback, and leaves FILE (a regular file) unchanged.
refused() {
  local reader=$1 file=$2 log before="" rc
  log="$reader.$(basename "$file").log"
  [ -f "$file" ] && before=$(sha256sum < "$file")
  read_with "$reader" "$file" "$log"
  rc=$?
  [ "$rc" != 124 ] || fail "$reader $file: no answer within 10 s"
  expect_status "$reader $file" "$rc" 2 "$log"
  one_line "$log" "$3"
  if grep -q 'Traceback' "$log"; then fail "$reader $file: a traceback: $(tr '\n' '|' < "$log")"; fi
  if [ -n "$before" ] && [ "$(sha256sum < "$file")" != "$before" ]; then
    fail "$reader $file: the file changed"
  fi
}

# The files as written open.
for pair in open_result:r.h5 open_sweep:s.h5 open_envelope:e.h5; do
  read_with "${pair%%:*}" "${pair#*:}" ok.log || fail "${pair%%:*} ${pair#*:}: $(cat ok.log)"
done

# Special files, refused before anything opens them (a FIFO would wait for a writer).
mkfifo fifo.h5
mkdir dir.h5
for reader in open_result open_sweep open_envelope; do
  refused "$reader" fifo.h5 "^hexdyn: error: fifo\.h5: is a FIFO, not a regular file$"
  refused "$reader" dir.h5 "^hexdyn: error: dir\.h5: is a directory, not a regular file$"
  refused "$reader" /dev/zero "^hexdyn: error: /dev/zero: is a device, not a regular file$"
done

# Copies with one dataset off the schema (h5py), not HDF5, cut short.
"$PY" - <<'PY' || fail "could not write the corrupted copies"
import shutil
import h5py
import numpy as np


def corrupt(src, dst, path, new):
    shutil.copy(src, dst)
    with h5py.File(dst, "r+") as f:
        old = f[path][()]
        del f[path]
        f[path] = new(old)


corrupt("r.h5", "time_text.h5", "time",
        lambda v: np.array([str(x) for x in v], dtype=h5py.string_dtype()))
corrupt("r.h5", "time_short.h5", "time", lambda v: v[:10])
corrupt("r.h5", "torque_17.h5", "joints/torque", lambda v: v[:, :17])
corrupt("r.h5", "phase_float.h5", "contacts/phase", lambda v: v.astype(np.float64))
corrupt("s.h5", "energy_short.h5", "scenarios/energy", lambda v: v[:-1])
corrupt("e.h5", "grid_flat.h5", "envelope/riser_max", lambda v: v.reshape(-1))
with open("text.h5", "w") as f:
    f.write("not HDF5\n")
with open("r.h5", "rb") as f, open("short.h5", "wb") as g:
    g.write(f.read()[:100000])
PY
refused open_result time_text.h5 "^hexdyn: error: time_text\.h5: dataset /time is string \([0-9]+,\), expected float64"
refused open_result time_short.h5 "^hexdyn: error: time_short\.h5: dataset /[a-z/_]+ is float64 \([0-9]+, .*expected float64 \(10, .*T = 10 from /time"
refused open_result torque_17.h5 "^hexdyn: error: torque_17\.h5: dataset /joints/torque is float64 \([0-9]+, 17\), expected float64 \([0-9]+, 18\)"
refused open_result phase_float.h5 "^hexdyn: error: phase_float\.h5: dataset /contacts/phase is float64 .*expected int8"
refused open_sweep energy_short.h5 "^hexdyn: error: energy_short\.h5: dataset /scenarios/energy is float64 \([0-9]+,\), expected float64 \([0-9]+,\) \(N = [0-9]+ from /scenarios/id\)$"
refused open_envelope grid_flat.h5 "^hexdyn: error: grid_flat\.h5: dataset /envelope/riser_max is float64 \([0-9]+,\), expected float64 \([0-9]+, [0-9]+, [0-9]+, [0-9]+\)"
for reader in open_result open_sweep open_envelope; do
  refused "$reader" text.h5 "^hexdyn: error: text\.h5: cannot be read as HDF5: "
  refused "$reader" short.h5 "^hexdyn: error: short\.h5: cannot be read as HDF5: "
done
echo "readers: special files and files off the schema refused in one line, none changed"
