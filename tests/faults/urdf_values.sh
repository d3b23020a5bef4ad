#!/bin/bash
# URDF values (docs/user/faults.md#sizes): a URDF's masses, inertias,
# origins and joint limits are held to the scene's plausibility bounds
# (src/hexdyn/core/value_bounds.hpp). The Kraby robot with one value edited beyond a bound
# (a <mass value="1e300"> that ran to NaN torques, an inertia, a joint origin, a joint limit,
# an effort) is refused by `run`, `validate`, a sweep's cases axis and an envelope's cases, in
# one line naming the file, the link or joint and the value: exit status 2, no output, the
# inputs unchanged. So is a sphere, box or cylinder of size 0 or below in a <collision> or
# <visual> (the Kraby's and the pexod's). Every real robot of the repository still loads.
# shellcheck source=common.sh
source "$(dirname "$0")/common.sh"

mkdir out
KRABY="$SRC/robots/kraby.urdf"
SCENE="$SRC/configs/robots/kraby_stairs.yaml"

# edited NAME PYTHON-EXPRESSION [URDF]: robots/kraby.urdf (or URDF) with its text passed
# through the expression (a function of `t`), as NAME.urdf; the expression must change the text.
edited() {
  "$PY" - "${3:-$KRABY}" "$2" > "$1.urdf" << 'EOF'
import re, sys
t = open(sys.argv[1]).read()
u = eval(sys.argv[2])
assert u != t, "the edit changed nothing"
print(u, end="")
EOF
}
edited heavy 're.sub(r"<mass value=\"[^\"]*\"", "<mass value=\"1e300\"", t, count=1)'
edited wide 're.sub(r"izz=\"[^\"]*\"", "izz=\"2000\"", re.sub(r"ixx=\"[^\"]*\"", "ixx=\"1500\"", re.sub(r"iyy=\"[^\"]*\"", "iyy=\"1500\"", t, count=1), count=1), count=1)'
edited far 're.sub(r"(<inertial>\s*<origin xyz=\")[^\"]*\"", lambda m: m.group(1) + "0 0 50\"", t, count=1)'
edited far_joint 're.sub(r"(<joint [^>]*>(?:(?!</joint>).)*?<origin xyz=\")[^\"]*\"", lambda m: m.group(1) + "0 -12 0\"", t, count=1, flags=re.S)'
edited turns 're.sub(r"upper=\"[^\"]*\"", "upper=\"20\"", t, count=1)'
edited strong 're.sub(r"effort=\"[^\"]*\"", "effort=\"1e9\"", t, count=1)'
edited point 're.sub(r"<sphere radius=\"[^\"]*\"", "<sphere radius=\"0\"", t, count=1)'
edited flat 're.sub(r"<box size=\"[^\"]*\"", "<box size=\"0.024 -0.0451 0.0347\"", t, count=1)'
edited short 're.sub(r"<cylinder length=\"[^\"]*\"", "<cylinder length=\"-0.06\"", t, count=1)' \
  "$SRC/robots/pexod.urdf"

{
  echo "base: $SCENE"
  echo "axes:"
  echo "  - name: robot"
  echo "    cases:"
  echo "      - {label: kraby, robot.urdf: $KRABY}"
  echo "      - {label: heavy, robot.urdf: heavy.urdf}"
} > cases.yaml
{
  echo "base: $SCENE"
  echo "riser: {from: 0.0, to: 0.05}"
  echo "duty_factor: [1/2]"
  echo "peak_speed: [0.05]"
  echo "cases:"
  echo "  - {label: heavy, robot.urdf: heavy.urdf}"
} > envelope.yaml

inputs_digest() { sha256sum ./*.urdf ./*.yaml "$KRABY" "$SCENE"; }
before=$(inputs_digest)


refused mass_run "heavy.urdf: link '[^']+': mass 1e\+300 kg, expected at most 10000 kg" \
  run "$SCENE" -o out/r.h5 --set robot.urdf=heavy.urdf
refused mass_validate "heavy.urdf: link '[^']+': mass 1e\+300 kg" \
  validate "$SCENE" --set robot.urdf=heavy.urdf
refused inertia "wide.urdf: link '[^']+': inertia too large: principal moments .* expected each at most 1000 kg m2" \
  run "$SCENE" -o out/r.h5 --set robot.urdf=wide.urdf
refused inertial_origin "far.urdf: link '[^']+': <inertial><origin xyz=\"0 0 50\">, expected coordinates within \+-10 m" \
  run "$SCENE" -o out/r.h5 --set robot.urdf=far.urdf
refused joint_origin "far_joint.urdf: joint '[^']+': <origin xyz=\"0 -12 0\">, expected coordinates within \+-10 m" \
  run "$SCENE" -o out/r.h5 --set robot.urdf=far_joint.urdf
refused limits "turns.urdf: joint '[^']+': limits \[.*, 20\] rad, expected limits within \[-4 pi, 4 pi\]" \
  run "$SCENE" -o out/r.h5 --set robot.urdf=turns.urdf
refused effort "strong.urdf: joint '[^']+': effort limit 1e\+09 N m, expected a number in \[0, 1e\+06\]" \
  run "$SCENE" -o out/r.h5 --set robot.urdf=strong.urdf
refused sphere "point.urdf: link '[^']+': <collision><sphere radius=\"0\">, expected a radius > 0 m$" \
  run "$SCENE" -o out/r.h5 --set robot.urdf=point.urdf
refused box "flat.urdf: link '[^']+': <collision><box size=\"0.024 -0.0451 0.0347\">, expected three sizes > 0 m$" \
  validate "$SCENE" --set robot.urdf=flat.urdf
refused cylinder "short.urdf: link 'leg_2_1': <visual><cylinder radius=\"0.02\" length=\"-0.06\">, expected a radius and a length > 0 m$" \
  run "$SRC/configs/robots/pexod_stairs.yaml" -o out/r.h5 --set "robot.urdf=$PWD/short.urdf"
refused sweep_case "cases.yaml: axes\[0\].cases\[1\] \(heavy: .*\): .*heavy.urdf: link '[^']+': mass 1e\+300 kg" \
  validate cases.yaml
refused envelope_case "envelope.yaml: cases\[0\] \(heavy: .*\): .*heavy.urdf: link '[^']+': mass 1e\+300 kg" \
  envelope envelope.yaml -o out/e.h5

# The real robots still load: every scene and sweep of configs/ that names a URDF (envelope
# files are loaded by `hexdyn envelope`, which computes), and each robot of robots/ and
# tests/data/urdf/robots/ on the Kraby or PhantomX scene (the HumaRobotics PhantomX is
# refused for its inertias, as before).
while IFS= read -r scene; do
  grep -qE "^(robot|axes):" "$scene" || continue
  timeout 120 "$HEXDYN" validate "$scene" > valid.log 2>&1 || fail "validate $scene: $(cat valid.log)"
done < <(grep -rl "urdf:" "$SRC/configs" --include=*.yaml)
for urdf in "$SRC"/robots/*.urdf "$SRC"/tests/data/urdf/robots/*.urdf; do
  [ -f "$urdf" ] || continue
  case "$(basename "$urdf")" in
    kraby.urdf) scene=$SCENE ;;
    phantomx_humarobotics.urdf) continue ;;
    # The quadrupeds are read whole; their model is refused until it holds four legs
    # (tests/hexdyn/model/test_urdf_legs.cpp).
    solo12.urdf | anymal_c.urdf) continue ;;
    *) scene="$SRC/configs/robots/phantomx_mark4_stairs.yaml" ;;
  esac
  timeout 60 "$HEXDYN" validate "$scene" --set "robot.urdf=$urdf" > valid.log 2>&1 ||
    fail "validate $urdf: $(cat valid.log)"
done
echo "urdf_values: every value beyond its bound refused in one line, the real robots load"
