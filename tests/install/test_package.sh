#!/usr/bin/env bash
# The Debian package (CPack, cmake/packaging.cmake) built from the install rules into a scratch
# folder: it holds the program, the Python package, the man page and the completion under /usr,
# and declares its dependencies (the shared libraries via dpkg-shlibdeps, python3 and its packages).
# Usage: test_package.sh BUILD_DIR PYTHON_DIR (PYTHON_DIR relative to the prefix).
set -euo pipefail
build=$1 pydir=$2
out=$(mktemp -d /tmp/tidalcrust-package.XXXXXX)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

(cd "$build" && cpack -G DEB -B "$out" > "$out/cpack.log" 2>&1) || { cat "$out/cpack.log"; fail "cpack -G DEB"; }
deb=$(ls "$out"/tidalcrust_*.deb 2>/dev/null | head -1)
[ -n "$deb" ] || { cat "$out/cpack.log"; fail "no tidalcrust_*.deb in $out"; }
contents=$(dpkg-deb -c "$deb")
for f in usr/bin/tidalcrust "usr/$pydir/tidalcrust/__init__.py" "usr/$pydir/tidalcrust/checkpoint.py" \
         usr/share/man/man1/tidalcrust.1 usr/share/bash-completion/completions/tidalcrust \
         usr/share/doc/tidalcrust/examples/quick-start.ipynb; do
  grep -q " \./$f\$" <<< "$contents" || fail "the package lacks /$f: $contents"
done
depends=$(dpkg-deb -f "$deb" Depends)
for d in libhdf5 libfmt libtomlplusplus3 libxxhash0 libudunits2-0 libsleef3 libgomp1 libstdc++6 libc6 python3 python3-h5py python3-numpy python3-xarray python3-matplotlib python3-cartopy; do
  grep -q "\(^\|, \)$d" <<< "$depends" || fail "Depends lacks $d: $depends"
done
[ "$(dpkg-deb -f "$deb" Package)" = tidalcrust ] || fail "package name: $(dpkg-deb -f "$deb" Package)"
echo "$(basename "$deb"): Depends: $depends"
