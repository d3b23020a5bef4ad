#!/bin/bash
# Links in a checkpoint: nothing in a checkpoint follows a link. A lock that is a link (to an
# input file, to a FIFO, to /dev/full), a FIFO, a hard link of an input, a journal that is
# a link, a checkpoint folder that is a link: each refused in one line naming it, exit 2,
# nothing written through it, no file left in a folder that is not the sweep's own.
# shellcheck source=common.sh
source "$(dirname "$0")/common.sh"

cp "$SRC/configs/sweeps/stairs_base.yaml" victim.yaml
before=$(md5sum < victim.yaml)
mkfifo fifo
mkdir -p y other

# refused NAME PATTERN [mpi]: a sweep onto y/s.h5 (1 rank, or 2 under mpirun) is refused.
refused() {
  local log="$1.log" rc
  if [ "${3:-}" = mpi ]; then
    mpi 2 sweep "$SMOKE" -o y/s.h5 --resume > "$log" 2>&1
  else
    "$HEXDYN" sweep "$SMOKE" -o y/s.h5 > "$log" 2>&1
  fi
  rc=$?
  expect_status "$1" "$rc" 2 "$log"
  one_line "$log" "$2"
  [ ! -e y/s.h5 ] || fail "$1: an output was written"
  [ "$(md5sum < victim.yaml)" = "$before" ] || fail "$1: the link's target was written"
}

mkdir y/s.h5.checkpoint
ln -s ../../victim.yaml y/s.h5.checkpoint/lock
refused lock_link_to_input "checkpoint lock 'y/s.h5.checkpoint/lock': it is a symbolic link"
refused lock_link_to_input_mpi "checkpoint lock 'y/s.h5.checkpoint/lock': it is a symbolic link" mpi
rm y/s.h5.checkpoint/lock
ln -s ../../fifo y/s.h5.checkpoint/lock
refused lock_link_to_fifo "checkpoint lock 'y/s.h5.checkpoint/lock': it is a symbolic link"
rm y/s.h5.checkpoint/lock
mkfifo y/s.h5.checkpoint/lock
refused lock_fifo "checkpoint lock 'y/s.h5.checkpoint/lock': it is a FIFO"
rm y/s.h5.checkpoint/lock
ln -s /dev/full y/s.h5.checkpoint/lock
refused lock_link_to_dev_full "checkpoint lock 'y/s.h5.checkpoint/lock': it is a symbolic link"
rm y/s.h5.checkpoint/lock
ln victim.yaml y/s.h5.checkpoint/lock
refused lock_hard_link "checkpoint lock 'y/s.h5.checkpoint/lock': it is a file with other \(hard\) links"
rm y/s.h5.checkpoint/lock
ln -s ../../victim.yaml y/s.h5.checkpoint/journal-0001.hxj
refused journal_link "checkpoint journal 'y/s.h5.checkpoint/journal-0001.hxj': it is a symbolic link"
rm -rf y/s.h5.checkpoint

# The checkpoint folder itself a link to another folder: refused, nothing left there.
ln -s ../other y/s.h5.checkpoint
refused folder_link "checkpoint directory 'y/s.h5.checkpoint': it is a symbolic link"
refused folder_link_mpi "checkpoint directory 'y/s.h5.checkpoint': it is a symbolic link" mpi
[ -z "$(ls -A other)" ] || fail "files left in the folder the link points to: $(ls -A other)"

# With the links gone the same sweep runs (the refusals were about the links only).
rm y/s.h5.checkpoint
"$HEXDYN" sweep "$SMOKE" -o y/s.h5 > ok.log 2>&1 || fail "the sweep without links failed: $(cat ok.log)"
[ -f y/s.h5 ] && [ ! -e y/s.h5.checkpoint ] || fail "no output, or the checkpoint was left"
echo "links: all refused in one line, nothing written through them"
