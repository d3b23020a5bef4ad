#!/bin/bash
# Inputs kept: no output is ever written onto an input, and a command uses each input
# as it was when first read. Every command (run, sweep, envelope, Python's Result.write) is
# pointed at each kind of input it reads (the scene, an inherited file, the URDF named in the
# scene or by --set, the base's and a case's URDF of a sweep, the sweep and envelope files
# themselves), by its own name, another name and a hard link: one line naming the input, exit
# status 2, every input byte for byte as before, nothing left behind. Then a URDF edited while
# a sweep runs: the sweep's scenarios all use the bytes read at its start (its summary equals
# that of a sweep of the original file) and /meta input_sha256 names those bytes.
# shellcheck source=common.sh
source "$(dirname "$0")/common.sh"
export PYTHONPATH="${PYTHONPATH:-$(dirname "$HEXDYN")/python}"

mkdir -p robots scenes
cp "$SRC/robots/phantomx_mark4.urdf" "$SRC/robots/kraby.urdf" robots/ ||
  fail "no URDF in $SRC/robots"
cat > scenes/common.yaml << 'EOF'
motion: {cycles: 1}
EOF
sed -e 's#urdf: .*#urdf: ../robots/phantomx_mark4.urdf#' \
  "$SRC/configs/robots/phantomx_mark4_stairs.yaml" > scenes/mark4.yaml
printf 'inherit: common.yaml\n' | cat - scenes/mark4.yaml > scenes/scene.yaml
rm scenes/mark4.yaml
cat > sweep.yaml << 'EOF'
base: scenes/scene.yaml
axes:
  - key: terrain.riser_height
    values: [0.02, 0.03]
  - cases:
      - {label: mark4, robot.urdf: robots/phantomx_mark4.urdf, robot.forward_axis: +x}
      - {label: kraby, robot.urdf: robots/kraby.urdf, robot.forward_axis: +y}
EOF
cat > envelope.yaml << 'EOF'
base: scenes/scene.yaml
riser: {from: 0.0, to: 0.04, step: 0.04, tolerance: 0.01}
tread_depth: [0.25]
duty_factor: [1/2]
peak_speed: [0.05]
criteria: [kinematic]
EOF
ln robots/kraby.urdf kraby_link.h5
sha256sum robots/* scenes/* sweep.yaml envelope.yaml > inputs.sha256
listing() { find . robots scenes -maxdepth 1 ! -name 'refused_*.log' | sort; }
before=$(listing)

in_line="which the output would destroy"
refused "run onto its URDF" "the URDF .*phantomx_mark4.urdf.*$in_line" \
  run scenes/scene.yaml -o robots/phantomx_mark4.urdf
refused "run onto its URDF by another name" "the URDF .*$in_line" \
  run scenes/scene.yaml -o scenes/../robots/./phantomx_mark4.urdf
refused "run onto a --set URDF" "the URDF 'robots/kraby.urdf'.*$in_line" \
  run scenes/scene.yaml --set robot.urdf=robots/kraby.urdf \
  --set robot.forward_axis=+y -o robots/kraby.urdf
refused "run onto a hard link of a --set URDF" "the URDF .*$in_line" \
  run scenes/scene.yaml --set robot.urdf=robots/kraby.urdf \
  --set robot.forward_axis=+y -o kraby_link.h5
refused "run onto its scene" "the scene .*$in_line" run scenes/scene.yaml -o scenes/scene.yaml
refused "run onto an inherited file" "the inherited scene .*common.yaml.*$in_line" \
  run scenes/scene.yaml -o scenes/common.yaml
refused "sweep onto its file" "the sweep file .*$in_line" sweep sweep.yaml -o sweep.yaml
refused "sweep onto the base's URDF" "the URDF .*phantomx_mark4.urdf.*$in_line" \
  sweep sweep.yaml -o robots/phantomx_mark4.urdf
refused "sweep onto a case's URDF" "the URDF .*kraby.urdf.*$in_line" \
  sweep sweep.yaml -o kraby_link.h5
refused "sweep onto the base's inherited file" "the inherited scene .*$in_line" \
  sweep sweep.yaml -o scenes/common.yaml
refused "envelope onto its own file" "the envelope file .*$in_line" \
  envelope envelope.yaml -o envelope.yaml
refused "envelope onto its URDF" "the URDF .*$in_line" \
  envelope envelope.yaml -o robots/phantomx_mark4.urdf
[ "$(listing)" = "$before" ] || fail "files appeared or went: $(diff <(echo "$before") <(listing) | tr '\n' ' ')"
no_temporaries . && no_temporaries robots && no_temporaries scenes

# Python's Result.write: the same refusals, by the identities and absolute paths of the files
# the run read, after a chdir, and a write that needs no input once the result is computed.
"$PY" - << 'EOF' || fail "Python's Result.write"
import os, shutil, hexdyn
r = hexdyn.run("scenes/scene.yaml")
os.makedirs("sub", exist_ok=True)
os.chdir("sub")
for target in ("../robots/phantomx_mark4.urdf", "../scenes/scene.yaml", "../scenes/common.yaml"):
    try:
        r.write(target)
    except hexdyn.IoError as e:
        assert "which the output would destroy" in str(e) and "\n" not in str(e), e
    else:
        raise AssertionError(f"wrote onto the input {target}")
os.chdir("..")
# The inputs gone: the computed result is still written.
shutil.move("scenes", "scenes_away")
shutil.move("robots", "robots_away")
r.write("after.h5")
# Moved, an input is still itself.
try:
    r.write("robots_away/phantomx_mark4.urdf")
except hexdyn.IoError as e:
    assert "the URDF" in str(e), e
else:
    raise AssertionError("wrote onto the moved URDF")
shutil.move("scenes_away", "scenes")
shutil.move("robots_away", "robots")
EOF
[ -s after.h5 ] || fail "Result.write after the inputs were gone wrote nothing"
sha256sum --quiet -c inputs.sha256 || fail "Python: an input changed"

# A URDF edited while a sweep runs: every scenario computes with the bytes read at the start.
cat > frozen.yaml << 'EOF'
base: scenes/scene.yaml
axes:
  - key: terrain.riser_height
    range: {from: 0.0, to: 0.06, count: 24}
EOF
"$HEXDYN" sweep frozen.yaml -o reference.h5 > ref.log 2>&1 || fail "reference sweep: $(cat ref.log)"
original=$(sha256sum robots/phantomx_mark4.urdf | cut -d' ' -f1)
# Each scenario waits 0.2 s on purpose (test-only switch, docs/user/sweeps.md), so the edit
# lands mid-sweep on an idle machine as on a busy one.
HEXDYN_TEST_HOLD_SECONDS=0.2 "$HEXDYN" sweep frozen.yaml -o edited.h5 > edited.log 2>&1 &
pid=$!
wait_for 'edited.h5.checkpoint/journal-*' 60 || fail "the sweep wrote no journal: $(cat edited.log)"
# Every mass doubled, in place (same inode): a robot whose torques differ everywhere.
"$PY" - << 'EOF'
import re
with open("robots/phantomx_mark4.urdf", "r+") as f:
    text = re.sub(r'<mass value="([^"]+)"', lambda m: f'<mass value="{2 * float(m[1])!r}"', f.read())
    f.seek(0)
    f.write(text)
    f.truncate()
EOF
edited=$(sha256sum robots/phantomx_mark4.urdf | cut -d' ' -f1)
[ "$edited" != "$original" ] || fail "the URDF was not edited"
kill -0 "$pid" 2> /dev/null || fail "the sweep ended before the edit: nothing was tested"
wait "$pid" || fail "the sweep with an edited URDF failed: $(cat edited.log)"
grep -q "wrote" edited.log || fail "no line of the sweep's output: $(cat edited.log)"
compare reference.h5 edited.h5 || fail "scenarios computed after the edit used the edited URDF"
"$PY" - "$original" << 'EOF' || fail "/meta input_sha256 does not name the bytes used"
import sys, h5py
text = h5py.File("edited.h5", "r")["meta"].attrs["input_sha256"]
text = text.decode() if isinstance(text, bytes) else text
line = [l for l in text.splitlines() if l.endswith("phantomx_mark4.urdf")]
assert line and line[0].split()[0] == sys.argv[1], text
EOF
# And the edited file is what a new command reads.
"$HEXDYN" run scenes/scene.yaml -o new.h5 > new.log 2>&1 || fail "run after the edit: $(cat new.log)"
"$PY" - "$edited" << 'EOF' || fail "a new run did not read the edited URDF"
import sys, h5py
text = h5py.File("new.h5", "r")["meta"].attrs["input_sha256"]
text = text.decode() if isinstance(text, bytes) else text
assert any(l.split()[0] == sys.argv[1] for l in text.splitlines()), text
EOF
echo "inputs: outputs never replace an input; a sweep keeps the bytes it read first"
