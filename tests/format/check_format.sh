#!/usr/bin/env bash
# Formatting check (ctest format.clang_format): every C++ file under src/, tests/, bench/,
# bindings/ and examples/ of SOURCE_DIR -- *.cpp, *.hpp, *.h and their .in templates -- must
# be exactly what clang-format makes of it with SOURCE_DIR/.clang-format. In a git checkout
# the files are the tracked ones plus untracked files not ignored; elsewhere every such file
# found.
#
#   tests/format/check_format.sh SOURCE_DIR
#
# Exit 0 when every file is formatted; 1 when some are not (each named, with its number of
# differences, and the command that fixes them) or when clang-format is missing. The
# project's formatting is that of Debian 12's clang-format 14 (package clang-format, in
# pipelines/setup.sh); CLANG_FORMAT=/path/to/clang-format chooses another binary.
set -uo pipefail

if [[ $# -ne 1 ]]; then
  echo "usage: $0 SOURCE_DIR" >&2
  exit 2
fi
root="$(cd "$1" && pwd)" || exit 2
style="$root/.clang-format"
clang_format="${CLANG_FORMAT:-clang-format}"

if ! command -v "$clang_format" >/dev/null 2>&1; then
  echo "format: '$clang_format' not found: install Debian's clang-format" \
       "(bash pipelines/setup.sh does) or set CLANG_FORMAT" >&2
  exit 1
fi
if [[ ! -f "$style" ]]; then
  echo "format: $style not found" >&2
  exit 1
fi

cd "$root" || exit 1
files=()
if git -C "$root" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  while IFS= read -r -d '' f; do
    [[ -f "$f" ]] && files+=("$f")
  done < <(git ls-files -z --cached --others --exclude-standard -- src tests bench bindings examples |
           grep -zE '\.(cpp|hpp|h)(\.in)?$' | sort -zu)
else
  while IFS= read -r -d '' f; do
    files+=("${f#./}")
  done < <(find src tests bench bindings examples -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' \
             -o -name '*.cpp.in' -o -name '*.hpp.in' -o -name '*.h.in' \) -print0 2>/dev/null |
           sort -z)
fi
if ((${#files[@]} == 0)); then
  echo "format: no C++ file under src/, tests/, bench/, bindings/ or examples/ of $root" >&2
  exit 1
fi

version="$("$clang_format" --version 2>/dev/null | head -n1)"
# One diagnostic "FILE:LINE:COL: error: code should be clang-formatted" per difference.
report="$("$clang_format" --style="file:$style" --dry-run --Werror "${files[@]}" 2>&1)"
status=$?
bad="$(printf '%s\n' "$report" |
       sed -nE 's/^(.+):[0-9]+:[0-9]+: (error|warning): code should be clang-formatted.*/\1/p' |
       sort | uniq -c)"

if [[ $status -eq 0 && -z "$bad" ]]; then
  echo "format: ${#files[@]} files formatted as .clang-format says ($version)"
  exit 0
fi
if [[ -z "$bad" ]]; then
  # clang-format failed without a formatting diagnostic (a file it cannot read, a bad style).
  printf '%s\n' "$report" >&2
  echo "format: $clang_format failed ($version)" >&2
  exit 1
fi
n=$(printf '%s\n' "$bad" | wc -l)
echo "format: $n of ${#files[@]} files differ from .clang-format ($version);" \
     "differences per file:"
printf '%s\n' "$bad" | sed -E 's/^ *([0-9]+) (.*)$/  \2: \1/'
if ((n <= 5)); then
  printf '%s\n' "$report" | head -n 60
fi
echo "format: fix with \`$clang_format -i FILE...\` on the files named above (paths from $root)"
exit 1
