#!/bin/bash
# Full disks: a full disk on every write path is one line naming the file with "No
# space left on device", exit status 2 (never 139), no temporary file, an existing good
# file kept; for a sweep the checkpoint is kept and a resume once space is freed gives
# the file of a sweep that never met a full disk. A small tmpfs, so root only.
# shellcheck source=common.sh
source "$(dirname "$0")/common.sh"
need_root "it mounts a small tmpfs to fill"

mkdir full
mount -t tmpfs -o size=300k tmpfs full || fail "cannot mount a tmpfs"
trap 'umount -l "$WORK/full" 2> /dev/null' EXIT

# fill: takes all the space left on the tmpfs.
fill() { dd if=/dev/zero of=full/filler bs=4k > /dev/null 2>&1; true; }

# run: the paper's result (0.9 MB) on 300 kB, over an existing good file.
echo good > full/paper.h5
"$HEXDYN" run "$PAPER" -o full/paper.h5 2> run.log
rc=$?
grep -v 'relaxed' run.log > run1.log
expect_status run "$rc" 2 run1.log
one_line run1.log "^hexdyn: error: cannot write 'full/paper.h5': No space left on device$"
[ "$(cat full/paper.h5)" = good ] || fail "run: the good file was not kept"
no_temporaries full

# envelope, the tmpfs filled to the last block
fill
"$HEXDYN" envelope "$SRC/tests/data/envelope_quick.yaml" -o full/e.h5 > env.log 2>&1
expect_status envelope $? 2 env.log
one_line env.log "^hexdyn: error: cannot write 'full/e.h5': No space left on device$"
[ ! -e full/e.h5 ] || fail "envelope: a file was written"
no_temporaries full
rm -f full/filler full/paper.h5

# Reference sweep, away from the tmpfs.
"$HEXDYN" sweep "$SMOKE" -o ref.h5 --keep-runs > ref.log 2>&1 || fail "reference sweep: $(cat ref.log)"

# sweep_case NAME RANKS SIZE WHERE: the kept-runs smoke sweep (1.2 MB file, 1.25 MB journal)
# on a tmpfs of SIZE; WHERE says which write meets the full disk.
sweep_case() {
  local name="$1" ranks="$2" size="$3" where="$4" log="$1.log" rc
  rm -rf full/*
  mount -o remount,size="$size" full
  if [ "$ranks" = 1 ]; then
    "$HEXDYN" sweep "$SMOKE" -o full/s.h5 --keep-runs > "$log" 2>&1
  else
    mpi "$ranks" sweep "$SMOKE" -o full/s.h5 --keep-runs > "$log" 2>&1
  fi
  rc=$?
  expect_status "$name" "$rc" 2 "$log"
  one_line "$log" "^hexdyn: error: cannot write $where: No space left on device \(finished scenarios are kept; continue with --resume\)$"
  [ ! -e full/s.h5 ] || fail "$name: an output was written"
  [ -d full/s.h5.checkpoint ] || fail "$name: the checkpoint was not kept"
  no_temporaries full
  mount -o remount,size=8m full
  "$HEXDYN" sweep "$SMOKE" -o full/s.h5 --keep-runs --resume > "$name.resume.log" 2>&1 ||
    fail "$name: the resume failed: $(cat "$name.resume.log")"
  compare ref.h5 full/s.h5 || fail "$name: the resumed file differs from the reference"
  [ ! -e full/s.h5.checkpoint ] || fail "$name: checkpoint left after the resume"
}
sweep_case final_write_1_rank 1 1800k "'full/s.h5'"
sweep_case final_write_2_ranks 2 1800k "'full/s.h5'"
sweep_case journal_2_ranks 2 300k "checkpoint journal 'full/s.h5.checkpoint/journal-0001.hxj'"
echo "full disk: one line, exit 2, temporaries removed, good files kept, resumes exact"
