#!/bin/bash
# The replay protects what it reads (docs/user/faults.md#replay): it never writes onto the
# result nor onto any file the result records (/meta input_sha256: the scene, the scene it
# inherits, the URDF) by name, another name, a link or a hard link; it replays the run from
# the result's own description (a URDF edited or removed since changes nothing but a
# warning); --set takes only replay.* and contact.* keys; every series it reads is checked
# (finite, unit quaternions, the feet where the stored joints put them); its work is bounded
# before it starts; a robot without a mass matrix names robot.leg_inertia. Each refusal: one
# line, exit status 2, every input byte for byte as before, nothing left behind.
# shellcheck source=common.sh
source "$(dirname "$0")/common.sh"
H5PY="$PY"

mkdir -p robots scenes
cp "$SRC/robots/phantomx_mark4.urdf" robots/ || fail "no URDF in $SRC/robots"
printf 'motion: {cycles: 1}\n' > scenes/common.yaml
sed -e 's#urdf: .*#urdf: ../robots/phantomx_mark4.urdf#' \
  "$SRC/configs/robots/phantomx_mark4_stairs.yaml" > scenes/mark4.yaml
printf 'inherit: common.yaml\n' | cat - scenes/mark4.yaml > scenes/scene.yaml
rm scenes/mark4.yaml
"$HEXDYN" run scenes/scene.yaml -o r.h5 > run.log 2>&1 || fail "the URDF run failed: $(cat run.log)"
ln -s robots linkdir
ln robots/phantomx_mark4.urdf hardlink.urdf
sha256sum r.h5 robots/* scenes/* > inputs.sha256

in_line="which the output would destroy"
refused "replay onto the result" "result file .*$in_line" replay r.h5 -o r.h5
refused "replay onto the URDF" "phantomx_mark4.urdf.*$in_line" \
  replay r.h5 -o robots/phantomx_mark4.urdf
refused "replay onto the URDF through a folder link" "phantomx_mark4.urdf.*$in_line" \
  replay r.h5 -o linkdir/phantomx_mark4.urdf
refused "replay onto the URDF's hard link" "phantomx_mark4.urdf.*$in_line" \
  replay r.h5 -o hardlink.urdf
refused "replay onto the scene" "scene.yaml.*$in_line" replay r.h5 -o scenes/scene.yaml
refused "replay onto the inherited scene" "common.yaml.*$in_line" \
  replay r.h5 -o scenes/../scenes/common.yaml
rm hardlink.urdf
sha256sum r.h5 robots/* scenes/* > inputs.sha256

# Keys a replay cannot honour.
refused "--set a robot key" "robot.tibia.length: .*replay.\* or contact.\*" \
  replay r.h5 -o o.h5 --set robot.tibia.length=0.5
refused "--set a gait key" "gait.duty_factor: .*replay.\* or contact.\*" \
  replay r.h5 -o o.h5 --set gait.duty_factor=3/4
# Unbounded work, refused before it starts.
refused "replay.step 1e-300" "replay.step: got 1e-300 s.*expected at most 1e\+06 steps" \
  replay r.h5 -o o.h5 --set replay.step=1e-300
refused "replay.step 1e-7" "replay.step: got 1e-07 s" replay r.h5 -o o.h5 --set replay.step=1e-7
refused "a missing result" "'nothing.h5' does not exist" replay nothing.h5 -o o.h5

# The stored description, not the disk: the same replay after the URDF's masses are
# multiplied by 40 (and after it is removed), with one warning line naming it.
"$HEXDYN" replay r.h5 -o p0.h5 --set replay.step=2e-3 > p0.log 2>&1 || fail "replay: $(cat p0.log)"
if grep -q "warning" p0.log; then fail "a warning with the inputs unchanged: $(cat p0.log)"; fi
cp robots/phantomx_mark4.urdf urdf.orig
sed -i -E 's/mass value="([0-9.]+)"/mass value="4\1"/' robots/phantomx_mark4.urdf
cmp -s urdf.orig robots/phantomx_mark4.urdf && fail "the URDF edit changed nothing"
"$HEXDYN" replay r.h5 -o p1.h5 --set replay.step=2e-3 > p1.log 2>&1 || fail "replay: $(cat p1.log)"
grep -q "warning: replay: the run's input '.*phantomx_mark4.urdf' has changed" p1.log ||
  fail "no warning of the edited URDF: $(cat p1.log)"
rm robots/phantomx_mark4.urdf
"$HEXDYN" replay r.h5 -o p2.h5 --set replay.step=2e-3 > p2.log 2>&1 || fail "replay: $(cat p2.log)"
grep -q "phantomx_mark4.urdf' is gone" p2.log || fail "no warning of the removed URDF: $(cat p2.log)"
sha256sum r.h5 scenes/* > inputs.sha256
refused "replay onto the removed URDF's path" "phantomx_mark4.urdf' \(the same path\), $in_line" \
  replay r.h5 -o robots/phantomx_mark4.urdf
[ ! -e robots/phantomx_mark4.urdf ] || fail "a file was written at the removed URDF's path"
"$H5PY" - << 'EOF' || fail "the replays differ"
import h5py, numpy as np
def energies(path):
    with h5py.File(path, "r") as f:
        return [f["/replay/energy"][()], f["/replay/actuator_work"][()],
                f["/base/position"][-1].tolist()]
a, b, c = energies("p0.h5"), energies("p1.h5"), energies("p2.h5")
assert a == b == c, (a, b, c)
EOF
cp urdf.orig robots/phantomx_mark4.urdf
sha256sum r.h5 robots/* scenes/* > inputs.sha256

# Results edited: a scene that is not the run's, and series that cannot be replayed.
edit() {  # edit COPY PYTHON-STATEMENT: a copy of r.h5 with f (h5py, r+) edited
  cp r.h5 "$1"
  "$H5PY" -c "import h5py, numpy as np
with h5py.File('$1', 'r+') as f:
    $2" || fail "cannot edit $1"
  sha256sum "$1" >> inputs.sha256
}
edit inf.h5 "d = f['/joints/position']; v = d[()]; v[7, 4] = np.inf; d[...] = v"
refused "an inf joint angle" "/joints/position at sample 7 holds inf, expected a finite number" \
  replay inf.h5 -o o.h5
edit quat.h5 "d = f['/base/orientation']; v = d[()]; v[3] = 0; d[...] = v"
refused "a zero quaternion" "/base/orientation at sample 3 has norm 0, expected a unit quaternion" \
  replay quat.h5 -o o.h5
edit half.h5 "d = f['/base/orientation']; v = d[()]; v[5] = [0.5, 0.5, 0, 0]; d[...] = v"
refused "a quaternion of norm 0.7" "/base/orientation at sample 5 has norm 0.707" \
  replay half.h5 -o o.h5

# The paper robot's description is its scene: a scene edited in /meta is not the run's.
"$HEXDYN" run "$PAPER" -o paper.h5 > paper.log 2>&1 ||
  fail "paper run: $(cat paper.log)"
sha256sum paper.h5 >> inputs.sha256
cp paper.h5 tibia.h5
"$H5PY" -c "import h5py, yaml
with h5py.File('tibia.h5', 'r+') as f:
    m = f['/meta']; c = yaml.safe_load(m.attrs['config_yaml'])
    c['robot']['tibia']['length'] *= 1.5
    m.attrs['config_yaml'] = yaml.safe_dump(c)" || fail "cannot edit tibia.h5"
sha256sum tibia.h5 >> inputs.sha256
refused "a scene that is not the run's" \
  "/feet/position of leg L1 at sample 0 .* m from where the stored joints and trunk put it" \
  replay tibia.h5 -o o.h5

# Massless legs: no mass matrix to integrate, named by the key that made it so.
"$HEXDYN" run "$PAPER" -o massless.h5 --set robot.leg_inertia=massless \
  > massless.log 2>&1 || fail "massless run: $(cat massless.log)"
sha256sum massless.h5 >> inputs.sha256
refused "massless legs" "robot.leg_inertia: .* has no mass" replay massless.h5 -o o.h5

# The fall test uses the robot's mass, not the trunk frame's origin, which Kraby's URDF puts
# 11 mm below its soles: its replay does not "fall" at its first step.
"$HEXDYN" run "$SRC/configs/robots/kraby_stairs.yaml" -o kraby.h5 > kraby.log 2>&1 ||
  fail "kraby run: $(cat kraby.log)"
"$HEXDYN" replay kraby.h5 -o kraby_replay.h5 --set replay.step=2e-3 > kraby_replay.log 2>&1 ||
  fail "kraby replay: $(cat kraby_replay.log)"
"$H5PY" - << 'EOF' || fail "Kraby's replay stopped early: $(cat kraby_replay.log)"
import h5py
with h5py.File("kraby.h5", "r") as plan, h5py.File("kraby_replay.h5", "r") as rep:
    message = rep["/replay/message"][()].decode()
    assert "fell" not in message, message
    assert rep["/time"].shape == plan["/time"].shape, (rep["/time"].shape, plan["/time"].shape)
EOF

# Progress lines, at the interval asked.
"$HEXDYN" replay r.h5 -o p3.h5 --set replay.step=2e-3 --progress 0 > p3.log 2>&1 ||
  fail "replay: $(cat p3.log)"
grep -qE '^hexdyn: replay: replay [0-9.e-]+ of [0-9.e-]+ s of motion \([0-9]+ %\)' p3.log ||
  fail "no progress line: $(head -c 600 p3.log)"
"$HEXDYN" run "$PAPER" -o p4.h5 --progress 0 > p4.log 2>&1 || fail "run: $(cat p4.log)"
grep -qE '^hexdyn: run: dynamics [0-9]+ of [0-9]+ samples \([0-9]+ %\)' p4.log ||
  fail "no progress line of run: $(head -c 600 p4.log)"
sha256sum --quiet -c inputs.sha256 || fail "an input changed"
no_temporaries .
echo "faults.replay: passed"
