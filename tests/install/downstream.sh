#!/usr/bin/env bash
# The installed C++ package, used as a downstream project would (cmake/install.cmake):
#   downstream.sh CMAKE BUILD_DIR SOURCE_DIR HEXDYN WORK_DIR [PYTHON]
# installs BUILD_DIR into a temporary prefix, configures and builds examples/custom_study/
# against that prefix alone (find_package(hexdyn), hexdyn::hexdyn: no dependency named), runs
# it on configs/paper.yaml with gait.duty_factor=3/4, and checks that its energy and its
# result file's datasets equal, bit for bit, those of the file `hexdyn run --set` writes for
# the same scene (but /solver/seconds, the clock's). Also checks the pkg-config file: a one-file program built with
# `pkg-config --cflags --libs hexdyn` alone links and runs.
set -euo pipefail
CMAKE="$1"
BUILD="$(realpath "$2")"
SRC="$(realpath "$3")"
HEXDYN="$4"
WORK="$5"
PY="${6:-/usr/bin/python3}"
fail() {
  echo "FAILED: $*" >&2
  exit 1
}
rm -rf "$WORK"
mkdir -p "$WORK"
P="$WORK/prefix"
"$CMAKE" --install "$BUILD" --prefix "$P" > "$WORK/install.log" 2>&1 || { cat "$WORK/install.log" >&2; fail "cmake --install"; }
for f in include/hexdyn/hexdyn.hpp include/hexdyn/version.hpp include/hexdyn/pipeline/pipeline.hpp \
         lib/cmake/hexdyn/hexdynConfig.cmake lib/cmake/hexdyn/hexdynConfigVersion.cmake \
         lib/cmake/hexdyn/hexdynTargets.cmake lib/pkgconfig/hexdyn.pc lib/libhexdyn_pipeline.a; do
  [ -f "$P/$f" ] || fail "not installed: $f"
done

# The downstream project sees the prefix only (no source tree, no build tree).
"$CMAKE" -S "$SRC/examples/custom_study" -B "$WORK/study" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$P" > "$WORK/configure.log" 2>&1 || { cat "$WORK/configure.log" >&2; fail "configure custom_study"; }
grep -rq "$SRC/src" "$WORK/study/CMakeCache.txt" "$WORK/study/CMakeFiles" 2>/dev/null &&
  fail "custom_study reached the source tree $SRC/src"
"$CMAKE" --build "$WORK/study" -j2 > "$WORK/build.log" 2>&1 || { cat "$WORK/build.log" >&2; fail "build custom_study"; }

cd "$WORK"
"$WORK/study/custom_study" "$SRC/configs/paper.yaml" gait.duty_factor=3/4 study.h5 > study.out ||
  fail "custom_study run"
"$HEXDYN" run "$SRC/configs/paper.yaml" --set gait.duty_factor=3/4 -o cli.h5 2> cli.log || { cat cli.log >&2; fail "hexdyn run"; }
"$PY" - study.out study.h5 cli.h5 <<'PYEOF'
import sys
import h5py
import numpy as np

out, study, cli = sys.argv[1:]
energy = float(next(l.split()[1] for l in open(out) if l.startswith("energy_total_J ")))
with h5py.File(cli, "r") as c, h5py.File(study, "r") as s:
    e_cli = float(c["/energy/total"][()])
    if energy != e_cli:
        sys.exit(f"custom_study energy {energy!r} J != hexdyn run's {e_cli!r} J")
    names = []
    c.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) else None)
    for n in names:
        a, b = c[n][()], s[n][()]
        if isinstance(a, np.ndarray) and a.dtype.kind == "f":
            same = a.shape == b.shape and a.tobytes() == b.tobytes()
        else:
            same = np.array_equal(np.asarray(a), np.asarray(b))
        if n != "solver/seconds" and not same:  # the clock's (time per solve)
            sys.exit(f"/{n} differs between custom_study's file and hexdyn run's")
print(f"custom_study: energy {energy!r} J, {len(names)} datasets, bit for bit those of hexdyn run")
PYEOF

# pkg-config alone.
cat > pc.cpp <<'CPP'
#include <hexdyn/hexdyn.hpp>
#include <cstdio>
int main(int, char** argv) {
  const hexdyn::Scene scene = hexdyn::load_scene(argv[1]);
  std::printf("%s %s\n", hexdyn::kVersion, scene.name.c_str());
}
CPP
PKG_CONFIG_PATH="$P/lib/pkgconfig" c++ -O1 pc.cpp -o pc $(PKG_CONFIG_PATH="$P/lib/pkgconfig" pkg-config --cflags --libs hexdyn) \
  2> pc.log || { cat pc.log >&2; fail "a program built with pkg-config hexdyn"; }
./pc "$SRC/configs/paper.yaml" > /dev/null || fail "the pkg-config program"
echo "downstream: ok"
