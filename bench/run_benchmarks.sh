#!/usr/bin/env bash
# Runs every benchmark executable (bench/*.cpp -> BUILD/bench/bench_*) with 5 repetitions
# and prints one table of medians.
#   bash bench/run_benchmarks.sh [BUILD_DIR] [extra Google Benchmark flags...]
# BUILD_DIR defaults to build/ next to this directory. The paper-run benchmark alone takes
# five whole paper runs (about 100 s); the balanced trunk's (bench_balanced_trunk: each balanced
# scene with the straight and the balanced trunk alternately) about 3 min.
# bench_dynamics_dart (the inverse dynamics against DART's) needs Debian's libdart-dev: run
# as root, the script installs it when missing and configures and builds the benchmarks
# again; otherwise that benchmark is skipped.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
build="${1:-$here/../build}"
shift || true
bench_dir="$build/bench"

# DART for bench_dynamics_dart (benchmark only; the library never links it).
src="$(cd "$here/.." && pwd)"
rebuild=0
dart=1
if ! dpkg -s libdart-dev >/dev/null 2>&1; then
  dart=0
  if [ "$(id -u)" -eq 0 ]; then
    echo "run_benchmarks.sh: installing libdart-dev for bench_dynamics_dart ..." >&2
    if DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends libdart-dev \
         >&2 ||
       { DEBIAN_FRONTEND=noninteractive apt-get update >&2 &&
         DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends libdart-dev \
           >&2; }; then
      rebuild=1
      dart=1
    else
      echo "run_benchmarks.sh: installing libdart-dev failed: bench_dynamics_dart skipped" >&2
    fi
  else
    echo "run_benchmarks.sh: libdart-dev not installed (run as root to install it):" \
         "bench_dynamics_dart skipped" >&2
  fi
elif [ ! -x "$bench_dir/bench_dynamics_dart" ]; then
  rebuild=1  # DART installed after this build directory was configured
fi
# The benchmarks are not in the default build: the target `benchmarks` builds them (again
# after DART was installed: the configuration finds it).
[ "$rebuild" -eq 1 ] && echo "run_benchmarks.sh: configuring $build for DART ..." >&2
cmake -S "$src" -B "$build" >/dev/null
if ! cmake --build "$build" -j"$(nproc)" --target benchmarks >&2; then
  echo "run_benchmarks.sh: building the benchmarks in $build failed (Google Benchmark:" \
       "Debian's libbenchmark-dev)" >&2
  exit 2
fi
if ! ls "$bench_dir"/bench_* >/dev/null 2>&1; then
  echo "run_benchmarks.sh: no benchmark executables in $bench_dir (build with Google Benchmark installed)" >&2
  exit 2
fi

out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
export HEXDYN_SOURCE_DIR="$src"
for exe in "$bench_dir"/bench_*; do
  [ -x "$exe" ] && [ -f "$exe" ] || continue
  name="$(basename "$exe")"
  # A bench_dynamics_dart left from before libdart-dev was removed cannot load DART.
  [ "$name" = bench_dynamics_dart ] && [ "$dart" -eq 0 ] && continue
  echo "running $name ..." >&2
  "$exe" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
         --benchmark_out="$out/$name.json" --benchmark_out_format=json "$@" >"$out/$name.txt" 2>&1 ||
    { cat "$out/$name.txt" >&2; echo "run_benchmarks.sh: $name failed" >&2; exit 1; }
done
/usr/bin/python3 - "$out" <<'PY'
import json, pathlib, sys
rows = []
skipped = set()
for path in sorted(pathlib.Path(sys.argv[1]).glob("*.json")):
    text = path.read_text()
    if not text.strip():  # a --benchmark_filter that matched nothing in this executable
        continue
    data = json.loads(text)
    for b in data["benchmarks"]:
        if b.get("error_occurred"):  # a skipped benchmark (a scene that throws): say why, once
            if (path.stem, b["run_name"]) not in skipped:
                skipped.add((path.stem, b["run_name"]))
                rows.append((path.stem, b["run_name"], float("nan"), float("nan"), "",
                             "skipped: " + b.get("error_message", "")[:100]))
            continue
        if b.get("aggregate_name") != "median":
            continue
        counters = {k: v for k, v in b.items()
                    if k in ("ipopt_iterations", "status", "samples", "relaxed_samples",
                             "ipopt_ratio", "hexdyn_us", "dart_us", "dart_ratio",
                             "max_abs_diff", "ratio", "balance_ms", "balance_share",
                             "per_call")}
        extra = " ".join(f"{k}={v:g}" for k, v in counters.items())
        rows.append((path.stem, b["run_name"], b["real_time"], b["cpu_time"], b["time_unit"], extra))
w = max([18] + [len(r[0]) for r in rows])
print(f"{'executable':<{w}} {'benchmark':<30} {'median wall':>14} {'median CPU':>14}  counters")
for exe, name, real, cpu, unit, extra in rows:
    print(f"{exe:<{w}} {name:<30} {real:>11.4g} {unit:<2} {cpu:>11.4g} {unit:<2}  {extra}")
PY
