#!/usr/bin/env bash
# Checks the tracked C++ sources (*.cpp, *.hpp under src/, tests/ and bench/) against
# .clang-format. Lists the files clang-format would change and exits 1; exits 0 when none.
# With --fix, formats those files in place instead (and lists them).
#   scripts/check_format.sh [--fix]
# The result depends on the clang-format version: the reference is Debian 12's clang-format 14
# (scripts/setup.sh installs it). CLANG_FORMAT=path picks another binary.
set -euo pipefail

usage() { echo "usage: check_format.sh [--fix]" >&2; }
die() { echo "check_format.sh: $*" >&2; exit 2; }

fix=0
if [ $# -gt 1 ]; then usage; exit 2; fi
case "${1-}" in
  "") ;;
  --fix) fix=1 ;;
  -h | --help) usage; exit 0 ;;
  *) usage; exit 2 ;;
esac

cd "$(dirname "$0")/.."
cf=${CLANG_FORMAT:-clang-format}
command -v "$cf" > /dev/null || die "$cf not found (scripts/setup.sh installs clang-format)"
[ -f .clang-format ] || die "no .clang-format in $(pwd)"
version=$("$cf" --version)
case "$version" in
  *"version 14."*) ;;
  *) echo "check_format.sh: warning: $version; the reference is clang-format 14" >&2 ;;
esac

# Tracked files only (git pathspecs: '*' also matches '/'); skip ones deleted in the work tree.
files=()
while IFS= read -r -d '' f; do
  [ -f "$f" ] && files+=("$f")
done < <(git ls-files -z -- 'src/*.cpp' 'src/*.hpp' 'tests/*.cpp' 'tests/*.hpp' \
                             'bench/*.cpp' 'bench/*.hpp')
[ ${#files[@]} -gt 0 ] || die "no tracked C++ files found"

bad=()
for f in "${files[@]}"; do
  if ! err=$("$cf" --style=file --dry-run -Werror "$f" 2>&1); then
    # A formatting difference reports -Wclang-format-violations; anything else is a failure of
    # clang-format itself (bad .clang-format, unreadable file) and stops the check.
    case "$err" in
      *clang-format-violations*) bad+=("$f") ;;
      *) echo "$err" >&2; die "clang-format failed on $f" ;;
    esac
  fi
done

if [ ${#bad[@]} -eq 0 ]; then
  echo "check_format.sh: all ${#files[@]} files formatted"
  exit 0
fi
if [ $fix -eq 1 ]; then
  "$cf" --style=file -i "${bad[@]}"
  printf '%s\n' "${bad[@]}"
  echo "check_format.sh: formatted ${#bad[@]} of ${#files[@]} files"
  exit 0
fi
printf '%s\n' "${bad[@]}"
echo "check_format.sh: ${#bad[@]} of ${#files[@]} files need formatting (scripts/check_format.sh --fix)" >&2
exit 1
