#!/usr/bin/env bash
# Every C++ source of the repository is formatted as .clang-format says:
# lists the files clang-format would change and fails if there is any.
#   bash Scripts/check-format.sh [CLANG_FORMAT]      (default: clang-format)
# To format them: clang-format -i FILE... (the same files, the same binary).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
format="${1:-clang-format}"
cd "$root"
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files '*.h' '*.cxx' '*.cpp' '*.hxx' '*.txx')
else
  mapfile -t files < <(find . -path ./build -prune -o -path './build-*' -prune -o \
    \( -name '*.h' -o -name '*.cxx' -o -name '*.cpp' -o -name '*.hxx' -o -name '*.txx' \) -print | sed 's|^\./||' | sort)
fi
if [[ ${#files[@]} -eq 0 ]]; then
  echo "check-format: no C++ file found under $root" >&2
  exit 1
fi
bad=()
for f in "${files[@]}"; do
  if ! "$format" --dry-run --Werror "$f" >/dev/null 2>&1; then
    bad+=("$f")
  fi
done
echo "check-format: ${#files[@]} files checked with $("$format" --version | head -n 1)"
if [[ ${#bad[@]} -gt 0 ]]; then
  printf 'check-format: not formatted (clang-format -i %s):\n' "${bad[*]}"
  printf '  %s\n' "${bad[@]}"
  exit 1
fi
echo "check-format: every file formatted"
