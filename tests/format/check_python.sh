#!/usr/bin/env bash
# Python lint (ctest format.python_lint): every Python file under analysis/, examples/,
# bindings/python/, tests/, bench/ and docs/ of SOURCE_DIR passes pyflakes (Debian 12's
# pyflakes3: unused imports and variables, undefined names, redefinitions, f-strings without
# placeholders). In a git checkout the files are the tracked ones plus untracked files not
# ignored; elsewhere every *.py found.
#
#   tests/format/check_python.sh SOURCE_DIR
#
# Exit 0 when pyflakes finds nothing; 1 when it reports something (each finding printed as
# FILE:LINE:COL: message) or when pyflakes3 is missing (package pyflakes3, in
# pipelines/setup.sh); PYFLAKES=/path/to/pyflakes chooses another binary.
set -uo pipefail

if [[ $# -ne 1 ]]; then
  echo "usage: $0 SOURCE_DIR" >&2
  exit 2
fi
root="$(cd "$1" && pwd)" || exit 2
pyflakes="${PYFLAKES:-pyflakes3}"
if ! command -v "$pyflakes" >/dev/null 2>&1; then
  echo "python_lint: '$pyflakes' not found: install Debian's pyflakes3" \
       "(bash pipelines/setup.sh does) or set PYFLAKES" >&2
  exit 1
fi

cd "$root" || exit 1
dirs=(analysis examples bindings/python tests bench docs)
files=()
if git -C "$root" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  while IFS= read -r -d '' f; do
    [[ -f "$f" ]] && files+=("$f")
  done < <(git ls-files -z --cached --others --exclude-standard -- "${dirs[@]}" |
           grep -zE '\.py$' | sort -zu)
else
  while IFS= read -r -d '' f; do
    files+=("${f#./}")
  done < <(find "${dirs[@]}" -type f -name '*.py' -print0 2>/dev/null | sort -z)
fi
if ((${#files[@]} == 0)); then
  echo "python_lint: no Python file under ${dirs[*]} of $root" >&2
  exit 1
fi

report="$("$pyflakes" "${files[@]}" 2>&1)"
status=$?
if [[ $status -eq 0 && -z "$report" ]]; then
  echo "python_lint: ${#files[@]} Python files pass $pyflakes"
  exit 0
fi
printf '%s\n' "$report"
n=$(printf '%s\n' "$report" | grep -c . || true)
echo "python_lint: $pyflakes reports $n findings in ${#files[@]} Python files (paths from $root)"
exit 1
