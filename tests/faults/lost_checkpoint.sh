#!/bin/bash
# A lost checkpoint: the checkpoint of a running sweep A is deleted, and a sweep B starts on
# the same output. A notices at its next append (or flush), stops in one line with exit
# status 2, writes no output and never touches B's checkpoint; B completes. Also: A's lock
# alone removed.
# shellcheck source=common.sh
source "$(dirname "$0")/common.sh"

mpi 2 sweep "$SLOW" -o v.h5 > a.log 2>&1 &
a=$!
wait_for 'v.h5.checkpoint/journal-*' 30 || fail "sweep A wrote no journal: $(cat a.log)"
rm -rf v.h5.checkpoint
"$HEXDYN" sweep "$SLOW" -o v.h5 > b.log 2>&1 &
b=$!
wait "$a"
rc=$?
[ "$rc" = 2 ] || fail "sweep A: exit status $rc, expected 2: $(cat a.log)"
one_line a.log "^hexdyn: error: the checkpoint 'v.h5.checkpoint' is no longer this sweep's: its directory was removed"
grep -q '^hexdyn: sweep: wrote' a.log && fail "sweep A wrote its output"
wait "$b" || fail "sweep B failed: $(cat b.log)"
grep -q '^hexdyn: sweep: wrote v.h5: 252 scenarios' b.log || fail "sweep B: $(cat b.log)"
[ ! -e v.h5.checkpoint ] || fail "checkpoint left behind"

# Only the lock removed: A stops all the same, its journal left for a resume.
rm -f v.h5
"$HEXDYN" sweep "$SLOW" -o w.h5 > c.log 2>&1 &
c=$!
wait_for 'w.h5.checkpoint/journal-*' 30 || fail "sweep C wrote no journal: $(cat c.log)"
rm w.h5.checkpoint/lock
wait "$c"
expect_status "lock removed" $? 2 c.log
one_line c.log "is no longer this sweep's: its lock was removed or replaced"
[ ! -e w.h5 ] || fail "sweep C wrote its output"
"$HEXDYN" sweep "$SLOW" -o w.h5 --resume > d.log 2>&1 || fail "resume after a lost lock: $(cat d.log)"
echo "lost checkpoint: the sweep stops in one line, exit 2, the other sweep completes"
