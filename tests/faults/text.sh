#!/bin/bash
# Text as UTF-8: text bound for a file must be UTF-8 (HDF5 readers decode hexdyn's strings
# as UTF-8). A scene, an inherited file, a URDF, a sweep file or a --set value holding bytes
# that are not UTF-8 is refused where it is read: one line naming the file (or --set), the
# line and column, exit status 2, no output file, the input untouched. Python's hexdyn.run
# raises hexdyn.ConfigError before computing (not a UnicodeDecodeError after), and a path
# holding a NUL is a ValueError that creates no file.
# shellcheck source=common.sh
source "$(dirname "$0")/common.sh"
export PYTHONPATH="${PYTHONPATH:-$(dirname "$HEXDYN")/python}"

cp "$PAPER" paper.yaml
printf 'name: "caf\xe9"\n' | cat paper.yaml - | grep -av '^name: paper' > latin1.yaml
printf 'inherit: latin1.yaml\n' > child.yaml
printf 'base: latin1.yaml\naxes:\n  - key: gait.duty_factor\n    values: [1/2]\n' > sweep.yaml
printf 'base: paper.yaml\nname: "\xff"\naxes:\n  - key: gait.duty_factor\n    values: [1/2]\n' > sweep_name.yaml
urdf="$SRC/robots/phantomx_mark4.urdf"
[ -n "$urdf" ] || fail "no URDF to test with"
sed 's#<robot name="\([^"]*\)"#<robot name="\1\xe9"#' "$urdf" > robot.urdf
grep -aq $'\xe9' robot.urdf || fail "the URDF was not made non-UTF-8"
sha256sum ./*.yaml robot.urdf > inputs.sha256

refused "scene" "latin1.yaml: not UTF-8 text: byte 0xE9 at line [0-9]+, column 11" \
  run latin1.yaml -o o.h5
refused "inherited file" "latin1.yaml: not UTF-8 text" run child.yaml -o o.h5
refused "validate" "latin1.yaml: not UTF-8 text" validate latin1.yaml
refused "--set" "^hexdyn: error: --set name=caf\.\.\.: not UTF-8 text: byte 0xE9 at line 1, column 9" \
  run paper.yaml --set name=$'caf\xe9' -o o.h5
refused "sweep's base" "latin1.yaml: not UTF-8 text" sweep sweep.yaml -o o.h5
refused "sweep file" "sweep_name.yaml: not UTF-8 text: byte 0xFF at line 2, column 8" \
  sweep sweep_name.yaml -o o.h5
refused "URDF" "robot.urdf: not UTF-8 text: byte 0xE9" \
  run "$SRC/configs/robots/phantomx_mark4_stairs.yaml" --set robot.urdf="$PWD/robot.urdf" -o o.h5

"$PY" - << 'EOF' || fail "Python"
import os, hexdyn
try:
    hexdyn.run("latin1.yaml")
except hexdyn.ConfigError as e:
    assert "not UTF-8 text" in str(e) and "\n" not in str(e), e
else:
    raise AssertionError("a non-UTF-8 scene ran")
for call in (lambda: hexdyn.run("paper.yaml\0junk"), lambda: hexdyn.validate("paper.yaml\0")):
    try:
        call()
    except ValueError as e:
        assert "NUL" in str(e), e
    else:
        raise AssertionError("a path with a NUL was taken")
assert not os.path.exists("o.h5")
EOF
echo "text: non-UTF-8 input refused where it is read, NUL paths refused in Python"
