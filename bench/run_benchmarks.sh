#!/usr/bin/env bash
# Runs every benchmark executable (bench/*.cpp -> BUILD/bench/bench_*) with 5 repetitions
# and prints one table of medians.
#   bash bench/run_benchmarks.sh [BUILD_DIR] [extra Google Benchmark flags...]
# BUILD_DIR defaults to build/ next to this directory. The paper-run benchmark alone takes
# five whole paper runs (about 100 s).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
build="${1:-$here/../build}"
shift || true
bench_dir="$build/bench"
if ! ls "$bench_dir"/bench_* >/dev/null 2>&1; then
  echo "run_benchmarks.sh: no benchmark executables in $bench_dir (build with Google Benchmark installed)" >&2
  exit 2
fi
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
export HEXDYN_SOURCE_DIR="$(cd "$here/.." && pwd)"
for exe in "$bench_dir"/bench_*; do
  [ -x "$exe" ] && [ -f "$exe" ] || continue
  name="$(basename "$exe")"
  echo "running $name ..." >&2
  "$exe" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
         --benchmark_out="$out/$name.json" --benchmark_out_format=json "$@" >"$out/$name.txt" 2>&1 ||
    { cat "$out/$name.txt" >&2; echo "run_benchmarks.sh: $name failed" >&2; exit 1; }
done
/usr/bin/python3 - "$out" <<'PY'
import json, pathlib, sys
rows = []
for path in sorted(pathlib.Path(sys.argv[1]).glob("*.json")):
    data = json.loads(path.read_text())
    for b in data["benchmarks"]:
        if b.get("aggregate_name") != "median":
            continue
        counters = {k: v for k, v in b.items()
                    if k in ("ipopt_iterations", "status", "samples", "relaxed_samples")}
        extra = " ".join(f"{k}={v:g}" for k, v in counters.items())
        rows.append((path.stem, b["run_name"], b["real_time"], b["cpu_time"], b["time_unit"], extra))
print(f"{'executable':<18} {'benchmark':<30} {'median wall':>14} {'median CPU':>14}  counters")
for exe, name, real, cpu, unit, extra in rows:
    print(f"{exe:<18} {name:<30} {real:>11.4g} {unit:<2} {cpu:>11.4g} {unit:<2}  {extra}")
PY
