#!/usr/bin/env bash
# `hexdyn envelope` with cases (tests/data/envelope_cases.yaml): the file holds the declared
# layout with the dimension `case` (plot_envelope.py --check), and each design's boundary
# equals that of an envelope file without cases whose set: holds the design's keys (the
# same search run separately per robot); xarray selects a design by its label.
#   cases.sh HEXDYN SOURCE_DIR PYTHON
set -euo pipefail
HEXDYN="$1" SRC="$2" PY="${3:-/usr/bin/python3}"
d=$(mktemp -d)
trap 'rm -rf "$d"' EXIT
cd "$d"
"$HEXDYN" envelope "$SRC/tests/data/envelope_cases.yaml" -o cases.h5 2> cases.log ||
  { cat cases.log; exit 1; }
"$PY" "$SRC/analysis/plot_envelope.py" cases.h5 plot --check --table > table.txt
grep -q "^kraby: tread" table.txt || { cat table.txt; echo "FAILED: no kraby table"; exit 1; }
for robot in mark4 kraby; do
  # The design's keys as set: entries of a plain envelope file, from the case line.
  line=$(grep "label: $robot," "$SRC/tests/data/envelope_cases.yaml")
  keys=$(sed -e "s/.*label: $robot, //" -e 's/}$//' -e "s#\.\./\.\./robots/#$SRC/robots/#" \
    <<< "$line")
  sed -e '/^cases:/,/^  - /d' -e '/^  - /d' \
      -e "s#^set: {\(.*\)}#set: {\1, $keys}#" \
      -e "s#^base: \.\./\.\./#base: $SRC/#" "$SRC/tests/data/envelope_cases.yaml" > "$robot.yaml"
  "$HEXDYN" envelope "$robot.yaml" -o "$robot.h5" 2> "$robot.log" || { cat "$robot.yaml" "$robot.log"; exit 1; }
done
"$PY" - <<'PY'
import numpy as np
from hexdyn import xr as hx
env = hx.open_envelope("cases.h5")
assert list(env["case"].values) == ["mark4", "kraby"], env["case"].values
assert env.riser_max.dims[0] == "case", env.riser_max.dims
for robot in ("mark4", "kraby"):
    alone = hx.open_envelope(f"{robot}.h5")
    for name in ("riser_max", "riser_fail", "posture_height", "posture_margin"):
        a = env[name].sel(case=robot).values
        b = alone[name].values
        assert np.array_equal(a, b, equal_nan=True), (robot, name, a, b)
    assert np.isfinite(alone.riser_max.values).all(), robot
heights = env.riser_max.sel(criterion="kinematic").values.ravel()
assert heights[0] != heights[1], heights  # two robots, two boundaries
print("envelope cases: ok", dict(zip(env["case"].values, heights)))
PY
