#!/bin/bash
# Leftovers: a temporary file `.NAME.tmp.PID` of a process that is gone, next to
# an output, is removed by the next run onto that output (run, sweep), which says so in one
# line; one of a live process, a link by that name and a file of another output are kept.
# shellcheck source=common.sh
source "$(dirname "$0")/common.sh"

gone=$(dead_pid)
echo stale > ".p.h5.tmp.$gone"
echo live > ".p.h5.tmp.$$"
echo other > ".q.h5.tmp.$gone"
echo target > target
gone2=$(dead_pid)
while [ "$gone2" = "$gone" ]; do gone2=$(dead_pid); done
ln -s target ".p.h5.tmp.$gone2"
"$HEXDYN" run "$PAPER" -o p.h5 2> run.log || fail "run: $(cat run.log)"
n=$(grep -c '^hexdyn: removed' run.log)
[ "$n" = 1 ] || fail "run: $n lines about removed files, expected 1: $(cat run.log)"
grep -q "^hexdyn: removed './.p.h5.tmp.$gone', the temporary file of process $gone, which is gone" run.log ||
  fail "run: $(grep removed run.log)"
[ ! -e ".p.h5.tmp.$gone" ] || fail "the stale temporary file is still there"
[ -f ".p.h5.tmp.$$" ] && [ -f ".q.h5.tmp.$gone" ] && [ -L ".p.h5.tmp.$gone2" ] ||
  fail "a file that must be kept was removed"
[ "$(cat target)" = target ] || fail "the link's target changed"

# A sweep's final file (a --keep-runs sweep killed in its final write leaves one).
echo stale > ".s.h5.tmp.$gone"
"$HEXDYN" sweep "$SMOKE" -o s.h5 > sweep.log 2>&1 || fail "sweep: $(cat sweep.log)"
grep -q "^hexdyn: removed './.s.h5.tmp.$gone'" sweep.log || fail "sweep: $(cat sweep.log)"
[ ! -e ".s.h5.tmp.$gone" ] || fail "the sweep's stale temporary file is still there"
echo "leftovers: removed and named, others kept"
