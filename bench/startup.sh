#!/usr/bin/env bash
# Start-up time of the command line: median wall time of N runs (default 20) of
# `hexdyn --version` and of `hexdyn validate configs/paper.yaml`, for each binary given
# (e.g. an older build's binary next to build/hexdyn). The binaries take turns run by run,
# so that a change of the machine's load hits them alike. Also prints how many shared
# libraries each loads and whether libmpi is among them (ldd).
#   bench/startup.sh [-n N] HEXDYN [HEXDYN ...]
set -euo pipefail
n=20
if [ "${1:-}" = "-n" ]; then n="$2"; shift 2; fi
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for _ in $(seq "$n"); do
  i=0
  for bin in "$@"; do
    for cmd in version validate; do
      args=(--version)
      [ "$cmd" = validate ] && args=(validate "$root/configs/paper.yaml")
      t0=$(date +%s%N)
      "$bin" "${args[@]}" > /dev/null 2>&1
      t1=$(date +%s%N)
      echo $(((t1 - t0) / 1000)) >> "$work/$i.$cmd"
    done
    i=$((i + 1))
  done
done
median() { sort -n "$1" | awk '{a[NR]=$1} END {m = (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2; printf "%.1f", m / 1000}'; }
i=0
for bin in "$@"; do
  echo "$bin: --version $(median "$work/$i.version") ms, validate paper.yaml $(median "$work/$i.validate") ms" \
       "(median of $n; $(ldd "$bin" | wc -l) shared libraries, libmpi: $(ldd "$bin" | grep -c libmpi || true))"
  i=$((i + 1))
done
