#!/usr/bin/env bash
# cmake --install into a scratch prefix: the program, the Python package, the man page and the
# bash completion are there, and work from there (not from the source tree).
# Usage: test_install.sh BUILD_DIR PYTHON PYTHON_DIR (PYTHON_DIR relative to the prefix).
set -euo pipefail
build=$1 python=$2 pydir=$3
prefix=$(mktemp -d /tmp/tidalcrust-install.XXXXXX)
trap 'rm -rf "$prefix"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

cmake --install "$build" --prefix "$prefix" > "$prefix.log" 2>&1 || { cat "$prefix.log"; rm -f "$prefix.log"; fail "cmake --install"; }
rm -f "$prefix.log"
for f in bin/tidalcrust "$pydir/tidalcrust/__init__.py" "$pydir/tidalcrust/checkpoint.py" \
         "$pydir/tidalcrust/cracks.py" "$pydir/tidalcrust/maps.py" "$pydir/tidalcrust/figures/__init__.py" \
         "$pydir/tidalcrust/figures/__main__.py" "$pydir/tidalcrust/figures/encounter.py" \
         "$pydir/tidalcrust/figures/plots.py" share/man/man1/tidalcrust.1 \
         share/bash-completion/completions/tidalcrust share/doc/tidalcrust/examples/quick-start.ipynb; do
  [ -f "$prefix/$f" ] || fail "$f is not installed under $prefix"
done
"$prefix/bin/tidalcrust" --help | grep -q '^  analyze ' || fail "the installed program's --help lists no analyze"
# The package imports from the prefix, outside the source tree.
got=$(cd / && env -u PYTHONPATH PYTHONPATH="$prefix/$pydir" "$python" -c \
      'import tidalcrust, sys; print(tidalcrust.__file__); print(tidalcrust.UNITS_NOTE[:18])')
case "$got" in "$prefix/$pydir/tidalcrust/__init__.py"*"model units G = M"*) ;; *) fail "import tidalcrust from the prefix gave: $got";; esac
# The installed program draws its figures with the installed package (figures/figure_script.hpp):
# an interpreter wrapper records the PYTHONPATH it is given.
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
cat > "$prefix/python-wrapper" <<WRAP
#!/bin/sh
echo "\$PYTHONPATH" > "$prefix/pythonpath.txt"
exec "$python" "\$@"
WRAP
chmod +x "$prefix/python-wrapper"
(cd / && env -u PYTHONPATH TIDALCRUST_PYTHON="$prefix/python-wrapper" "$prefix/bin/tidalcrust" run \
   "$source_dir/tests/python/small.toml" --out "$prefix/run" --quiet) || fail "the installed program's run failed"
[ "$(cut -d: -f1 "$prefix/pythonpath.txt")" = "$prefix/$pydir" ] \
  || fail "the installed program's figures ran with PYTHONPATH $(cat "$prefix/pythonpath.txt")"
[ -f "$prefix/run/A/analysis/fracture_map.png" ] || fail "the installed program drew no fracture_map.png"
# The man page has every command of --help; the completion completes them and their options.
for cmd in $("$prefix/bin/tidalcrust" --help | sed -n 's/^  \([a-z][a-z]*\)  .*/\1/p'); do
  grep -q "^\.SS $cmd\$" "$prefix/share/man/man1/tidalcrust.1" || fail "man page lacks command $cmd"
done
completion=$(bash -c 'source "$1"; COMP_WORDS=(tidalcrust ana); COMP_CWORD=1; _tidalcrust; echo "${COMPREPLY[*]}";
                     COMP_WORDS=(tidalcrust run --dt); COMP_CWORD=2; _tidalcrust; echo "${COMPREPLY[*]}"' _ \
             "$prefix/share/bash-completion/completions/tidalcrust")
[ "$completion" = $'analyze\n--dt-factor' ] || fail "completion gave: $completion"
echo "installed: $(cd "$prefix" && find . -type f | sort | tr '\n' ' ')"
