#!/usr/bin/env bash
# Edited inputs: a resume must not mix two robots. A URDF sweep is killed part-way (kill -9 of
# mpirun), the URDF's mass is edited, and the --resume is refused: exit 2, one line naming the
# URDF, no output file, the checkpoint untouched. The same for an edit of the inherited scene
# file. With every input restored the resume completes, and the file's /meta input_sha256
# lists the sweep file, the base scene, the inherited scene and the URDF with the digests
# coreutils' sha256sum gives.
source "$(dirname "$0")/common.sh"
cp "$SRC/robots/kraby.urdf" kraby.urdf
sed 's|urdf: ../../robots/kraby.urdf|urdf: kraby.urdf|' "$SRC/configs/robots/kraby_stairs.yaml" > robot.yaml
grep -q "urdf: kraby.urdf" robot.yaml || fail "robot.yaml does not name the copied URDF"
printf 'inherit: robot.yaml\nname: edited_inputs\n' > scene.yaml
# The Ipopt back end keeps the scenarios slow enough to be killed part-way.
cat > sweep.yaml <<'YAML'
base: scene.yaml
set:
  allocation.solver: ipopt
  output.grid: uniform
axes:
  - key: terrain.riser_height
    values: [0.02, 0.03, 0.04, 0.05]
  - key: gait.duty_factor
    values: [1/2, 2/3, 3/4]
YAML

"$MPIEXEC" --oversubscribe -np 2 "$HEXDYN" sweep sweep.yaml -o k.h5 2> cut.log &
launcher=$!
cp=k.h5.checkpoint
kill_after_rows "$launcher" "$cp" 2 cut.log
"$PY" "$SRC/tests/sweep/journal_rows.py" "$cp" > before.txt
before=$(wc -l < before.txt)
[ "$before" -lt 12 ] || fail "every scenario was checkpointed before the kill"
journal_sum=$(cat "$cp"/*.hxj | sha256sum)

# refused FILE ROLE: the resume is refused in one line naming FILE, nothing written.
refused() {
  local file="$1" role="$2" rc=0
  mpi 2 sweep sweep.yaml -o k.h5 --resume > out.txt 2> err.txt || rc=$?
  [ "$rc" -eq 2 ] || { cat err.txt; fail "resume after editing $file: exit $rc, expected 2"; }
  # One line of hexdyn's (mpirun adds its own about the exit status).
  [ "$(grep -c '^hexdyn' err.txt)" -eq 1 ] || { cat err.txt; fail "resume after editing $file: not one line"; }
  grep -q "the $role $PWD/$file changed since the checkpoint was made" err.txt ||
    { cat err.txt; fail "the refusal does not name the $role $file"; }
  [ ! -e k.h5 ] || fail "a refused resume wrote k.h5"
  [ "$(cat "$cp"/*.hxj | sha256sum)" = "$journal_sum" ] || fail "a refused resume changed the checkpoint"
  echo "edited $file: refused ($(grep '^hexdyn' err.txt))"
}

cp kraby.urdf kraby.urdf.orig
sed -i 's|<mass value="0.667" />|<mass value="1.667" />|' kraby.urdf
cmp -s kraby.urdf kraby.urdf.orig && fail "the URDF's mass was not edited"
refused kraby.urdf URDF
mv kraby.urdf.orig kraby.urdf

cp robot.yaml robot.yaml.orig
sed -i 's|stroke: 0.025 |stroke: 0.026 |' robot.yaml
cmp -s robot.yaml robot.yaml.orig && fail "the inherited scene was not edited"
refused robot.yaml "inherited scene"
mv robot.yaml.orig robot.yaml

mpi 2 sweep sweep.yaml -o k.h5 --resume 2> resume.log || { cat resume.log; fail "resume with every input restored"; }
grep -q "taken from the checkpoint" resume.log || { cat resume.log; fail "the resume took nothing from the checkpoint"; }
"$PY" - k.h5 <<'PY'
import subprocess
import sys
import h5py
with h5py.File(sys.argv[1], "r") as f:
    got = f["meta"].attrs["input_sha256"]
files = ["sweep.yaml", "scene.yaml", "robot.yaml", "kraby.urdf"]
want = subprocess.run(["sha256sum"] + [f"{__import__('os').getcwd()}/{n}" for n in files],
                      capture_output=True, text=True, check=True).stdout
assert got == want, f"/meta input_sha256:\n{got}\nexpected (sha256sum):\n{want}"
PY
echo "edited inputs: ok ($before scenarios checkpointed before the kill)"
