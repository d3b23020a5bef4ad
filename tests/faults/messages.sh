#!/bin/bash
# Messages (docs/user/faults.md#inputs): input that is not what a command takes is refused in
# one line naming the key, file or argument, the value and what is allowed; exit status 2,
# nothing written, every input unchanged.
# - A quoted number where a number is expected ("1e-2", '0.05', !!str 200; in a list, a
#   sweep's set: and range, an envelope's list): YAML and Python read it as a string.
#   Numbers given by --set and Python's set= (text parsed as YAML), p/q, and quoted values of
#   string keys are still taken; every scene and sweep of configs/ still validates.
# - An HDF5 file (a result, also one with a 512-byte user block) or a binary file given as a
#   scene, sweep, envelope, inherited file or URDF: named as such, before its size.
# - A missing scene, URDF, inherited file or sweep base: "does not exist".
# - A URDF whose legs are not 2 to 8 chains of 3 to 6 moving joints (a leg too short or too
#   long, a chain that branches, two legs sharing a link, a foot not found, 9 legs, 1 leg, a
#   hip on the centre line): the leg and the link named.
# And an output name of up to 255 bytes is written: its temporary name is cut to fit
# (`.START~DIGEST.tmp.PID`), and a stale one of that form is removed by the next run.
# shellcheck source=common.sh
source "$(dirname "$0")/common.sh"
export PYTHONPATH="${PYTHONPATH:-$(dirname "$HEXDYN")/python}"

mkdir out
cp "$PAPER" paper.yaml
KRABY_SCENE="$SRC/configs/robots/kraby_stairs.yaml"
"$HEXDYN" run paper.yaml -o r.h5 > run.log 2>&1 || fail "run: $(cat run.log)"

# Quoted numbers.
printf 'inherit: paper.yaml\noutput:\n  tolerance: "1e-2"\n' > double.yaml
printf "inherit: paper.yaml\noutput:\n  tolerance: '0.05'\n" > single.yaml
printf 'inherit: paper.yaml\noutput:\n  impact_samples: !!str 200\n' > str.yaml
printf 'inherit: paper.yaml\ngait:\n  duty_factor: "3/4"\n' > fraction.yaml
printf 'inherit: paper.yaml\nmotion:\n  cycle_durations: [3.0, "2.6", 3.0]\n' > list.yaml
printf 'inherit: paper.yaml\nname: "2024"\nterrain:\n  type: "stairs"\n' > strings.yaml
# gait.phases (docs/user/configuration.md#gait): not a map, an unknown leg, a leg missing, a leg
# named twice, a phase outside [0, 1).
phases='L2: 0.5, L3: 0.5, L4: 0, L5: 0, L6: 0.5'
printf 'inherit: paper.yaml\ngait:\n  phases: [0, 0.5, 0.5, 0, 0, 0.5]\n' > phases_list.yaml
printf 'inherit: paper.yaml\ngait:\n  phases: {L1: 0, %s, L7: 0}\n' "$phases" > phases_name.yaml
printf 'inherit: paper.yaml\ngait:\n  phases: {%s}\n' "$phases" > phases_missing.yaml
printf 'inherit: paper.yaml\ngait:\n  phases:\n    L1: 0\n    L1: 0.5\n' > phases_twice.yaml
printf 'inherit: paper.yaml\ngait:\n  phases: {L1: 1, %s}\n' "$phases" > phases_range.yaml
# A per-leg key of a quadruped (Solo-12: four legs) given for another count of legs.
printf 'inherit: %s\nrobot:\n  nominal_pose: [[0, 0.8, -1.6], [0, 0.8, -1.6], [0, 0.8, -1.6]]\n' \
  "$SRC/configs/robots/solo12_flat.yaml" > quad_pose.yaml
axis='axes:\n  - key: gait.duty_factor\n    values: [1/2, 2/3]\n'
printf "base: paper.yaml\nset: {output.tolerance: \"1e-2\"}\n$axis" > sweep_set.yaml
printf "base: paper.yaml\naxes:\n  - key: terrain.riser_height\n    range: {from: 0.0, to: '0.07', count: 3}\n" \
  > sweep_range.yaml
printf "base: paper.yaml\naxes:\n  - name: design\n    cases:\n      - {label: a, output.tolerance: \"0.05\"}\n" \
  > sweep_case.yaml
sed -e "s#^base: .*#base: $SRC/configs/sweeps/stairs_base.yaml#" \
  -e 's/^peak_speed: \[0.05,/peak_speed: ["0.05",/' "$SRC/configs/envelope/paper.yaml" > envelope.yaml
grep -q '^peak_speed: \["0.05",' envelope.yaml || fail "the envelope file was not edited"

# Binary inputs: hexdyn's own program (larger than 1 MiB), a NUL in YAML text, HDF5 with a
# 512-byte user block (its signature at offset 512, not 0).
cp "$HEXDYN" program.yaml
printf 'name: a\0b\n' > nul.yaml
"$PY" - << 'EOF' || fail "the HDF5 file with a user block"
import h5py
with h5py.File("userblock.h5", "w", userblock_size=512) as f:
    f["x"] = [1.0]
data = open("userblock.h5", "rb").read()
sig = b"\x89HDF\r\n\x1a\n"
assert data[:8] != sig and data[512:520] == sig, "no user block"
EOF
printf 'inherit: r.h5\n' > inherits_result.yaml
printf 'inherit: missing.yaml\n' > inherits_missing.yaml
printf "base: missing.yaml\n$axis" > sweep_missing.yaml

inputs_digest() { sha256sum ./*.yaml ./*.h5 "$PAPER" "$KRABY_SCENE"; }
before=$(inputs_digest)

refused double_quoted 'double\.yaml: output\.tolerance: got the string "1e-2", expected a number in \[0, 0\.1\] \(write it unquoted\)$' \
  run double.yaml -o out/o.h5
refused single_quoted 'single\.yaml: output\.tolerance: got the string "0\.05", expected a number in \[0, 0\.1\] \(write it unquoted\)$' \
  validate single.yaml
refused str_tag 'str\.yaml: output\.impact_samples: got the string "200", expected an integer in \[1, [0-9]+\] \(write it unquoted\)$' \
  run str.yaml -o out/o.h5
refused fraction 'fraction\.yaml: gait\.duty_factor: got the string "3/4", expected a number in .* \(write it unquoted\)$' \
  validate fraction.yaml
refused list_item 'list\.yaml: motion\.cycle_durations\[1\]: got the string "2\.6", expected a number in .* \(write it unquoted\)$' \
  run list.yaml -o out/o.h5
refused set_quoted 'output\.tolerance: got the string "1e-2", expected .* \(write it unquoted\)$' \
  run paper.yaml --set 'output.tolerance="1e-2"' -o out/o.h5
refused sweep_set 'sweep_set\.yaml \(base .*paper\.yaml\): output\.tolerance: got the string "1e-2", expected a number in \[0, 0\.1\] \(write it unquoted\)$' \
  sweep sweep_set.yaml -o out/o.h5
refused sweep_range "sweep_range\.yaml: axes\[0\]\.range\.to: got the string \"0\.07\", expected a finite number \(write it unquoted\)$" \
  validate sweep_range.yaml
refused sweep_case 'sweep_case\.yaml: axes\[0\]\.cases\[0\] \(a: .*\): output\.tolerance: got the string "0\.05", expected .* \(write it unquoted\)$' \
  sweep sweep_case.yaml -o out/o.h5
refused envelope_list 'envelope\.yaml: peak_speed\[0\]: got the string "0\.05", expected a number in .* \(write it unquoted\)$' \
  envelope envelope.yaml -o out/o.h5

refused phases_list 'phases_list\.yaml: gait\.phases: got \[0, 0\.5, 0\.5, 0, 0, 0\.5\], expected a map \{L1: φ, …, L6: φ\} naming every leg once \(L1, L2, L3, L4, L5, L6\), each φ a lift-off phase in \[0, 1\)$' \
  validate phases_list.yaml
refused phases_name 'phases_name\.yaml: gait\.phases: got the key L7, expected leg names \(L1, L2, L3, L4, L5, L6\)$' \
  run phases_name.yaml -o out/o.h5
refused quad_pose 'quad_pose\.yaml: robot\.nominal_pose: got \[\[0, 0\.8, -1\.6\], \[0, 0\.8, -1\.6\], \[0, 0\.8, -1\.6\]\], expected \[coxa, femur, tibia\] rad, each a number in \[-6\.28319, 6\.28319\] \(every leg\); or 4 of them: a list in leg order L1 … L4, or a map by leg name L1 … L4$' \
  validate quad_pose.yaml
refused phases_missing 'phases_missing\.yaml: gait\.phases: got \{L2: 0\.5, .*\}, expected a map naming every leg once \(L1, .*\), L1 missing$' \
  validate phases_missing.yaml
refused phases_twice 'phases_twice\.yaml: gait\.phases\.L1: duplicate key, first at line 4, again at line 5' \
  validate phases_twice.yaml
refused phases_range 'phases_range\.yaml: gait\.phases\.L1: got 1, expected a number in \[0, 1\)$' \
  run phases_range.yaml -o out/o.h5
refused phases_set 'gait\.phases\.L4: got -0\.25, expected a number in \[0, 1\)$' \
  run paper.yaml --set "gait.phases={L1: 0, L2: 0.5, L3: 0.5, L4: -0.25, L5: 0, L6: 0.5}" -o out/o.h5

# Still taken: numbers by --set (p/q too) and by Python's set=, quoted strings. The value used
# is read back from the result's resolved scene.
"$HEXDYN" validate strings.yaml > valid.log 2>&1 || fail "quoted strings: $(cat valid.log)"
"$HEXDYN" run paper.yaml --set output.tolerance=1e-2 --set gait.duty_factor=3/4 -o set.h5 \
  > set.log 2>&1 || fail "--set numbers: $(cat set.log)"
"$PY" - << 'EOF' || fail "numbers by --set and set="
import h5py, hexdyn, yaml
with h5py.File("set.h5", "r") as f:
    config = yaml.safe_load(f["/meta"].attrs["config_yaml"])
assert config["output"]["tolerance"] == 0.01, config["output"]
assert config["gait"]["duty_factor"] == 0.75, config["gait"]
r = hexdyn.run("paper.yaml", set={"output.tolerance": 1e-2, "gait.duty_factor": "3/4"})
config = yaml.safe_load(r.meta["config_yaml"])
assert config["output"]["tolerance"] == 0.01 and config["gait"]["duty_factor"] == 0.75
try:
    hexdyn.validate("double.yaml")
except hexdyn.ConfigError as e:
    assert 'got the string "1e-2"' in str(e) and "\n" not in str(e), e
else:
    raise AssertionError("a quoted number was taken")
EOF
rm set.h5
# The height map the rough_map examples name is made by a script (pipelines/terrain.sh makes it
# under results/): made here, and named by --set.
"$PY" "$SRC/analysis/make_rough_map.py" "$PWD/rough_map.npy" > /dev/null || fail "make_rough_map.py"
while IFS= read -r f; do
  # envelope and study files are read by `hexdyn envelope` and analysis/study.py
  grep -qE "^(riser|targets):" "$f" && continue
  map=()
  grep -q "^  type: height_map" "$f" && map=(--set "terrain.height_map.file=$PWD/rough_map.npy")
  timeout 120 "$HEXDYN" validate "$f" "${map[@]}" > valid.log 2>&1 || fail "validate $f: $(cat valid.log)"
done < <(find "$SRC/configs" -name '*.yaml')

# HDF5 and binary files.
hdf5='is an HDF5 file \(a result, sweep or envelope file\?\), not text'
refused result_run "^hexdyn: error: r\.h5: $hdf5, expected a configuration file" run r.h5 -o out/o.h5
refused result_validate "^hexdyn: error: r\.h5: $hdf5, expected a configuration file" validate r.h5
refused result_sweep "^hexdyn: error: r\.h5: $hdf5" sweep r.h5 -o out/o.h5
refused result_envelope "^hexdyn: error: r\.h5: $hdf5" envelope r.h5 -o out/o.h5
refused result_inherited "r\.h5: $hdf5" validate inherits_result.yaml
refused result_urdf "r\.h5: $hdf5, expected a URDF file" \
  run "$KRABY_SCENE" --set "robot.urdf=$PWD/r.h5" -o out/o.h5
refused user_block "^hexdyn: error: userblock\.h5: $hdf5" run userblock.h5 -o out/o.h5
refused program "^hexdyn: error: program\.yaml: is a binary file \(a NUL byte at offset [0-9]+\), not text, expected a configuration file" \
  run program.yaml -o out/o.h5
refused nul "^hexdyn: error: nul\.yaml: is a binary file \(a NUL byte at offset 7\), not text" \
  validate nul.yaml

# Missing files.
refused missing_scene "^hexdyn: error: missing\.yaml: does not exist, expected a configuration file" \
  run missing.yaml -o out/o.h5
refused missing_urdf "robot\.urdf: got .*missing\.urdf, which does not exist" \
  run "$KRABY_SCENE" --set "robot.urdf=$PWD/missing.urdf" -o out/o.h5
refused missing_inherited "inherits_missing\.yaml: inherit: got missing\.yaml, which does not exist" \
  validate inherits_missing.yaml
refused missing_base "sweep_missing\.yaml: base: got missing\.yaml, .*missing\.yaml does not exist\)$" \
  sweep sweep_missing.yaml -o out/o.h5

# URDF leg layouts (docs/user/robots.md#legs): 2 to 8 legs of 3 to 6 moving joints each, in
# a chain; each broken layout is refused naming the leg and the link.
"$PY" - << 'EOF' || fail "writing the URDF leg layouts"
def robot(legs, extra=""):
    """legs: (x, y, joints) of each hip in the trunk link frame (x forward, y left)."""
    inertial = ('<inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" '
                'ixy="0" ixz="0" iyz="0"/></inertial>')
    out = ['<robot name="layout">', f'<link name="trunk">{inertial}</link>']
    for i, (x, y, n) in enumerate(legs):
        parent = "trunk"
        for j in range(1, n + 1):
            link, xyz = f"leg{i}_l{j}", f"{x} {y} 0" if j == 1 else f"0 {0.05 if y > 0 else -0.05} 0"
            out.append(f'<link name="{link}">{inertial}</link>')
            out.append(joint(f"leg{i}_j{j}", parent, link, xyz, "0 0 1" if j == 1 else "1 0 0"))
            parent = link
        out.append(f'<link name="leg{i}_foot"/><joint name="leg{i}_foot_fixed" type="fixed">'
                   f'<parent link="{parent}"/><child link="leg{i}_foot"/>'
                   f'<origin xyz="0 {0.1 if y > 0 else -0.1} -0.05"/></joint>')
    return "\n".join(out) + extra + "\n</robot>\n"
def joint(name, parent, child, xyz, axis):
    return (f'<joint name="{name}" type="revolute"><parent link="{parent}"/><child link="{child}"/>'
            f'<origin xyz="{xyz}"/><axis xyz="{axis}"/>'
            '<limit lower="-2" upper="2" effort="2" velocity="5"/></joint>')
def extra(name, parent, child):
    return f'<link name="{child}"/>' + joint(name, parent, child, "0 0.05 0", "1 0 0")
four = [(0.2, 0.1, 3), (0.2, -0.1, 3), (-0.2, 0.1, 3), (-0.2, -0.1, 3)]
files = {
    "two_joints": robot([four[0], (0.2, -0.1, 2)] + four[2:]),
    "seven_joints": robot([(0.2, 0.1, 7)] + four[1:]),
    "branch": robot(four, extra("spur", "leg2_l1", "spur_link")),
    "shared": robot(four, extra("twin2", "leg3_l1", "twin_l2") + extra("twin3", "twin_l2", "twin_l3")),
    "no_foot": robot(four, '<link name="sensor"/><joint name="sensor_fixed" type="fixed">'
                     '<parent link="leg0_l3"/><child link="sensor"/><origin xyz="0 0 0.01"/></joint>'),
    "nine_legs": robot([(0.4 - 0.1 * i, -0.1 if i % 2 else 0.1, 3) for i in range(9)]),
    "one_leg": robot(four[:1]),
    "centre_hip": robot(four[:2] + [(-0.2, 0.0, 3)]),
}
for name, text in files.items():
    open(f"{name}.urdf", "w").write(text)
EOF
layout() { refused "$1" "$1\.urdf: $2" validate "$KRABY_SCENE" --set "robot.urdf=$PWD/$1.urdf" --set robot.forward_axis=+x; }
layout two_joints "leg L2 \(chain 'leg1_j1'\): 2 moving joints from the trunk to its last link 'leg1_l2', expected 3 to 6$"
layout seven_joints "leg L1 \(chain 'leg0_j1'\): joint 'leg0_j7' leaves link 'leg0_l6' after 6 moving joints, expected 3 to 6 moving joints from the trunk to the foot$"
layout branch "leg L3 \(chain 'leg2_j1'\): the chain branches at link 'leg2_l1' \(moving joints 'leg2_j2', 'spur' leave it\)"
layout shared "leg L4 \(chain 'leg3_j1'\): two legs share link 'leg3_l1' \(moving joints 'leg3_j2', 'twin2' leave it\)"
layout no_foot "leg L1 \(chain 'leg0_j1'\): links 'leg0_foot' and 'sensor' are both fixed to 'leg0_l3'"
layout nine_legs "trunk 'trunk': 9 moving joints leave the trunk \('leg0_j1', .*\), expected at most 8 legs$"
layout one_leg "trunk 'trunk': 1 moving joints leave the trunk \('leg0_j1', the first joint of each leg\), expected at least 2 legs$"
layout centre_hip "chain 'leg2_j1' \(link 'leg2_l1'\): hip on the trunk's forward axis"

# Output names up to NAME_MAX (255 bytes): 250 letters and .h5, and 254 bytes with two-byte
# characters (the cut temporary name then ends on a whole character).
mkdir long
for name in "$(printf 'a%.0s' {1..250}).h5" "a$(printf '\xc3\xa9%.0s' {1..125}).h5"; do
  gone=$(dead_pid)
  stale=$("$PY" - "$name" "$gone" << 'EOF'
import hashlib, os, sys
name = os.fsencode(sys.argv[1])
assert len(name) <= 255
keep = 255 - len(b".") - len(b".tmp.") - 10 - 17  # the pid's 10 digits, '~' and 16 hex digits
while name[keep] & 0xC0 == 0x80:
    keep -= 1
stem = name[:keep] + b"~" + hashlib.sha256(name).hexdigest()[:16].encode()
sys.stdout.write(os.fsdecode(b"." + stem + b".tmp." + sys.argv[2].encode()))
EOF
  )
  echo stale > "long/$stale"
  "$HEXDYN" run paper.yaml -o "long/$name" > long.log 2>&1 || fail "run -o a long name: $(cat long.log)"
  [ -f "long/$name" ] || fail "no file written at the long name"
  [ ! -e "long/$stale" ] || fail "the stale temporary file of the long name was kept"
  grep -qF "removed 'long/$stale', the temporary file of process $gone" long.log ||
    fail "no line about the stale temporary file: $(cat long.log)"
  no_temporaries long
  "$PY" - "long/$name" << 'EOF' || fail "the file at the long name is not the run's result"
import sys, h5py, numpy
with h5py.File(sys.argv[1], "r") as f, h5py.File("r.h5", "r") as g:
    assert numpy.array_equal(f["/joints/torque"][()], g["/joints/torque"][()])
EOF
done
# A sweep's output needs room for its checkpoint folder, OUT.checkpoint: a longer name is
# one line saying how long it may be, and nothing is created.
long_sweep="long/$(printf 'b%.0s' {1..245}).h5"
refused "a sweep output name without room for .checkpoint" "expected an output file name of at most 244 bytes" \
  sweep "$SRC/configs/sweeps/smoke.yaml" -o "$long_sweep"
[ -z "$(find long -name 'bbb*')" ] || fail "the long sweep left files: $(ls long)"
echo "messages: quoted numbers, HDF5 and binary files, missing files, URDF leg layouts refused in one line; long output names written"
