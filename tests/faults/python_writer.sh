#!/bin/bash
# Python's writer of a read result (Result.write of open_result and Sweep.run,
# docs/user/faults.md#pythons-writer): SIGTERM and SIGHUP sent from outside during the write
# of a 98 MB result, signals raised at fixed points of the write (during the copy, before the
# sync, after the rename), Ctrl-C, names of 250 and 255 characters, and a full disk (a small
# tmpfs, root only: without root this part is skipped, exit 77, after the others ran). Each
# fault gives one line (hexdyn's error, printed by a small wrapper that exits with 2 as the CLI
# does, or the write's own line), exit status 2 or 128 + signal, no temporary file, and an
# existing file at the target byte for byte as it was; a write that completes gives a file
# whose datasets are the source's.
# shellcheck source=common.sh
source "$(dirname "$0")/common.sh"
# The package hexdyn of the build tree, unless the caller (ctest) names one.
export PYTHONPATH="${PYTHONPATH:-$(dirname "$HEXDYN")/python}"

# write.py SOURCE TARGET: open_result(SOURCE).write(TARGET); hexdyn's error as the CLI prints
# it, exit status 2.
cat > write.py << 'EOF'
import sys
import hexdyn
res = hexdyn.open_result(sys.argv[1])
print("read", flush=True)
try:
    res.write(sys.argv[2])
except hexdyn.Error as e:
    print(f"hexdyn: error: {e}", file=sys.stderr)
    sys.exit(2)
EOF

# inject.py WHERE SIG SOURCE TARGET: the write with the signal SIG sent by the process to itself
# (kill(2), delivered as any other) at WHERE: "copy" (before the first object is copied),
# "sync" (the bytes written, before fsync) or "rename" (right after the rename). Ctrl-C's
# KeyboardInterrupt exits with 42 after checking that the handlers are Python's again.
cat > inject.py << 'EOF'
import os, signal, sys
import h5py
import hexdyn
where, sig, source, target = sys.argv[1], getattr(signal, "SIG" + sys.argv[2]), *sys.argv[3:]
signal.signal(signal.SIGINT, signal.default_int_handler)  # a script's own, not inherited
res = hexdyn.open_result(source)
def hooked(real, after=False):
    def call(*args, **kwargs):
        if not after:
            os.kill(os.getpid(), sig)
        out = real(*args, **kwargs)
        if after:
            os.kill(os.getpid(), sig)
        return out
    return call
if where == "copy":
    h5py.Group.copy = hooked(h5py.Group.copy)
elif where == "sync":
    os.fsync = hooked(os.fsync)
else:
    os.replace = hooked(os.replace, after=True)
try:
    res.write(target)
except KeyboardInterrupt as e:
    print(f"KeyboardInterrupt: {e}", file=sys.stderr)
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler, "SIGINT not restored"
    assert signal.getsignal(signal.SIGTERM) == signal.SIG_DFL, "SIGTERM not restored"
    sys.exit(42)
print("write returned", file=sys.stderr)
EOF

# same_file A B: the datasets of the result files A and B are equal, bit for bit, and so
# are their attributes (hexdyn.open_result).
same_file() {
  "$PY" - "$1" "$2" << 'EOF'
import sys
import numpy as np
import hexdyn
a, b = (hexdyn.open_result(p) for p in sys.argv[1:3])
assert set(a) == set(b), set(a) ^ set(b)
for path in a:
    x, y = a[path], b[path]
    if isinstance(x, np.ndarray) and x.dtype.kind in "fiub":  # bit for bit, NaN included
        same = x.dtype == y.dtype and x.shape == y.shape and x.tobytes() == y.tobytes()
    else:
        same = list(np.ravel(x)) == list(np.ravel(y)) if isinstance(x, np.ndarray) else x == y
    assert same, f"{sys.argv[2]}: {path} differs from {sys.argv[1]}"
assert a.meta == b.meta and a.attrs == b.attrs
EOF
}

# kept FILE DIGEST WHAT: FILE is byte for byte the file of SHA-256 DIGEST.
kept() {
  [ "$(sha256sum < "$1")" = "$2" ] || fail "$3: the existing file $1 was not kept"
}

# The sources: the paper's result (0.6 MB) and one of 98 MB (8000 samples per touchdown
# transient; no required friction, as in signals.sh: the signals are the point).
"$HEXDYN" run "$PAPER" -o paper.h5 2> run.log || fail "run: $(cat run.log)"
"$HEXDYN" run "$PAPER" -o big.h5 --set output.impact_samples=8000 \
  --set output.required_friction=false 2> big.log || fail "run big: $(cat big.log)"
mkdir out
cp paper.h5 good.h5  # an existing good file at the targets
good=$(sha256sum < good.h5)

# 1. Signals sent from outside while the big result is written over a good file. Once the
# temporary file appears the writer is stopped (SIGSTOP) and, if the temporary file is still
# there, sent the signal and continued: the signal lands during the write however busy the
# machine is. A write that ended before the stop is tried again.
signal_write() {
  local sig=$1 status=$2 attempt pid rc i log="out_$1.log"
  for attempt in 1 2 3 4 5; do
    cp good.h5 out/big.h5
    "$PY" write.py big.h5 out/big.h5 > "$log" 2>&1 &
    pid=$!
    wait_for 'out/.big.h5.tmp.*' 120 || fail "SIG$sig: the write never started: $(cat "$log")"
    kill -STOP "$pid"
    for ((i = 0; i < 200; i++)); do
      [ "$(sed 's/^.*) //' "/proc/$pid/stat" 2> /dev/null | cut -d' ' -f1)" = T ] && break
      sleep 0.01
    done
    if compgen -G 'out/.big.h5.tmp.*' > /dev/null; then
      kill -"$sig" "$pid"
      kill -CONT "$pid"
      wait "$pid"
      rc=$?
      if grep -q "arrived after out/big.h5 was complete" "$log"; then
        # Stopped between its last look and the rename: the file is complete and kept.
        expect_status "SIG$sig after the rename" "$rc" "$status" "$log"
        same_file big.h5 out/big.h5 || fail "SIG$sig late: the file is not the source's"
        echo "note: SIG$sig came after the rename (attempt $attempt); again"
        continue
      fi
      expect_status "SIG$sig during the write" "$rc" "$status" "$log"
      one_line "$log" "^hexdyn: write interrupted by SIG$sig: nothing written to out/big.h5 \(an existing file there is kept, no temporary file left\)$"
      kept out/big.h5 "$good" "SIG$sig"
      no_temporaries out
      return
    fi
    kill -CONT "$pid"
    wait "$pid" || fail "SIG$sig: the write failed: $(cat "$log")"
    echo "note: the write ended before it could be stopped (attempt $attempt); again"
  done
  fail "SIG$sig: no attempt caught the write"
}
signal_write TERM 143
signal_write HUP 129
rm -f big.h5 out/big.h5  # 98 MB each

# 2. Signals at fixed points of the write, over a good file (paper.h5 onto out/p.h5).
injected() {
  local where=$1 sig=$2 status=$3 log="inject_$1_$2.log"
  cp good.h5 out/p.h5
  "$PY" inject.py "$where" "$sig" paper.h5 out/p.h5 > "$log" 2>&1
  expect_status "SIG$sig at $where" $? "$status" "$log"
  no_temporaries out
}
for case in copy:TERM sync:HUP sync:TERM copy:USR1; do
  where=${case%%:*} sig=${case#*:}
  status=$((128 + $(kill -l "$sig")))
  injected "$where" "$sig" "$status"
  one_line "inject_${where}_$sig.log" "^hexdyn: write interrupted by SIG$sig: nothing written to out/p.h5 \(an existing file there is kept, no temporary file left\)$"
  kept out/p.h5 "$good" "SIG$sig at $where"
done
# Ctrl-C: KeyboardInterrupt with the line, the handlers restored, nothing written.
injected sync INT 42
grep -q "^KeyboardInterrupt: write interrupted by SIGINT: nothing written to out/p.h5" \
  inject_sync_INT.log || fail "Ctrl-C: $(cat inject_sync_INT.log)"
kept out/p.h5 "$good" "Ctrl-C"
# A signal right after the rename: the file is complete, the line says so.
rm out/p.h5
injected rename TERM 143
grep -qx "hexdyn: write: SIGTERM arrived after out/p.h5 was complete; it is kept" \
  inject_rename_TERM.log || fail "SIGTERM after the rename: $(cat inject_rename_TERM.log)"
same_file paper.h5 out/p.h5 || fail "SIGTERM after the rename: the file is not the source's"
# SIGPIPE, ignored by Python, is left to it: the write completes.
rm out/p.h5
injected sync PIPE 0
same_file paper.h5 out/p.h5 || fail "SIGPIPE: the file is not the source's"

# 3. Names of 250 and 255 characters (the longest a Linux file system admits): their
# temporary names fit too, and the file is the source's.
for n in 250 255; do
  name="out/$(printf 'n%.0s' $(seq $((n - 3)))).h5"
  "$PY" write.py paper.h5 "$name" > "name_$n.log" 2>&1 || fail "a $n-character name: $(cat "name_$n.log")"
  same_file paper.h5 "$name" || fail "a $n-character name: the file is not the source's"
  no_temporaries out
  rm "$name"
done

# 4. A full disk: a 300 kB tmpfs, over a good file and on the tmpfs filled to its last block:
# one line with the OS's reason, exit status 2 (never a crash in HDF5), no temporary file.
need_root "it mounts a small tmpfs to fill"
mkdir full
mount -t tmpfs -o size=300k tmpfs full || fail "cannot mount a tmpfs"
trap 'umount -l "$WORK/full" 2> /dev/null' EXIT
echo good > full/paper.h5
small=$(sha256sum < full/paper.h5)
"$PY" write.py paper.h5 full/paper.h5 > full1.log 2>&1
expect_status "full disk" $? 2 full1.log
one_line full1.log "^hexdyn: error: cannot write 'full/paper.h5': No space left on device$"
kept full/paper.h5 "$small" "full disk"
no_temporaries full
dd if=/dev/zero of=full/filler bs=4k > /dev/null 2>&1
"$PY" write.py paper.h5 full/new.h5 > full2.log 2>&1
expect_status "full disk, last block" $? 2 full2.log
one_line full2.log "^hexdyn: error: cannot write (output )?'full/new.h5': No space left on device$"
[ ! -e full/new.h5 ] || fail "full disk, last block: a file was written"
no_temporaries full
echo "Python's writer: one line, 2 or 128 + signal, no temporary file, good files kept"
