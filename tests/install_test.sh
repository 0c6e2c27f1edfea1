#!/usr/bin/env bash
# The installed program runs without the source tree (ctest -R InstalledTree, README "Installing"):
#   1. `cmake --install BUILD_DIR` into a temporary prefix: the layout is there, and the installed
#      vrsph, started from an empty folder, finds its shipped cases (`vrsph check cases/...`,
#      `vrsph bench --time 0.0001`) under PREFIX/share/vrsph, also after the tree is moved;
#      VRSPH_DATA_DIR overrides the folder;
#   2. `cpack -G DEB` (when cpack and dpkg-deb are there): the package's control fields and
#      files, and its vrsph, extracted with `dpkg-deb -x`, run the same way.
# Usage: tests/install_test.sh BUILD_DIR
set -euo pipefail

build=$(cd "$1" && pwd)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/vrsph_install_test.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/work"
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-2}

fail() {
  echo "install_test: $*" >&2
  exit 1
}

# expect_in TEXT PATTERN WHAT: fails naming WHAT unless TEXT contains PATTERN (fixed string).
expect_in() {
  grep -qF -- "$2" <<<"$1" || fail "$3: expected '$2' in:"$'\n'"$1"
}

# check_tree PREFIX: the files of the layout, then the installed vrsph run from an empty folder.
check_tree() {
  local prefix=$1 out
  for f in bin/vrsph share/vrsph/cases/droplet_2d.toml share/vrsph/cases/bench_dam_break_2d.toml \
    share/vrsph/reference/dam_break_front.csv share/vrsph/scripts/plot_run.sh \
    share/doc/vrsph/README.md share/doc/vrsph/LICENSE share/doc/vrsph/docs/cases.md \
    share/doc/vrsph/docs/outputs.md; do
    [ -e "$prefix/$f" ] || fail "$prefix/$f is missing"
  done
  cd "$tmp/work"
  out=$("$prefix/bin/vrsph" check cases/droplet_2d.toml) || fail "vrsph check failed: $out"
  expect_in "$out" "reading $prefix/share/vrsph/cases/droplet_2d.toml" "check of a shipped case"
  expect_in "$out" "case droplet_2d (2D) is valid" "check of a shipped case"
  out=$("$prefix/bin/vrsph" bench --time 0.0001) || fail "vrsph bench failed: $out"
  expect_in "$out" "bench bench_dam_break_2d:" "bench with the shipped case"
  cd - >/dev/null
}

# 1. cmake --install into a prefix.
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
check_tree "$tmp/prefix"
mv "$tmp/prefix" "$tmp/moved"  # relocatable: the data is found from the executable's folder
check_tree "$tmp/moved"

# VRSPH_DATA_DIR overrides the folder: a folder without the cases is named in the error.
cd "$tmp/work"
set +e
out=$(VRSPH_DATA_DIR="$tmp/nowhere" "$tmp/moved/bin/vrsph" bench --time 0.0001 2>&1)
rc=$?
set -e
cd - >/dev/null
[ "$rc" -eq 1 ] || fail "bench with VRSPH_DATA_DIR=$tmp/nowhere: exit $rc, expected 1: $out"
expect_in "$out" "$tmp/nowhere/cases/bench_dam_break_2d.toml" "VRSPH_DATA_DIR override"
mkdir -p "$tmp/data/cases"
cp "$tmp/moved/share/vrsph/cases/droplet_2d.toml" "$tmp/data/cases/"
out=$(cd "$tmp/work" && VRSPH_DATA_DIR="$tmp/data" "$tmp/moved/bin/vrsph" check cases/droplet_2d.toml)
expect_in "$out" "reading $tmp/data/cases/droplet_2d.toml" "VRSPH_DATA_DIR override"

# 2. The Debian package.
if ! command -v cpack >/dev/null || ! command -v dpkg-deb >/dev/null; then
  echo "install_test: cpack or dpkg-deb missing: the .deb is not checked"
  exit 0
fi
cpack --config "$build/CPackConfig.cmake" -G DEB -B "$tmp/pkg" >/dev/null
deb=$(ls "$tmp"/pkg/vrsph_*.deb)
fields=$(dpkg-deb -f "$deb" Package Version Architecture Depends)
expect_in "$fields" "Package: vrsph" "control fields"
expect_in "$fields" "libgomp1" "Depends (dpkg-shlibdeps)"
dpkg-deb -x "$deb" "$tmp/deb"
check_tree "$tmp/deb/usr"
echo "install_test: ok ($(basename "$deb"), $(du -k "$deb" | cut -f1) KiB)"
