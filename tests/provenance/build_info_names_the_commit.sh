#!/bin/bash
# cmake/write_build_info.cmake names the commit of the source tree it is run on, with "-dirty" when
# tracked files differ from it, and rewrites the header only when that changes (so an unchanged
# commit recompiles nothing). Usage: build_info_names_the_commit.sh SOURCE_DIR
set -euo pipefail
source_dir=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
repo=$work/repo
mkdir -p "$repo"
git -C "$repo" init -q
echo one > "$repo/file"
git -C "$repo" add file
git -C "$repo" -c user.name=t -c user.email=t@t commit -q -m one
write() {
  cmake -DSOURCE_DIR="$repo" -DTEMPLATE="$source_dir/cmake/build_info.hpp.in" -DOUTPUT="$work/build_info.hpp" \
        -DPROJECT_VERSION=9.9 "-DCOMPILER=GNU 1" "-DFLAGS=-O2" -P "$source_dir/cmake/write_build_info.cmake"
}
fail() { echo "FAILED: $*"; cat "$work/build_info.hpp"; exit 1; }
write
first=$(git -C "$repo" rev-parse --short=12 HEAD)
grep -q "git_commit = \"$first\";" "$work/build_info.hpp" || fail "header does not name $first"
grep -q 'compiler = "GNU 1";' "$work/build_info.hpp" || fail "compiler not recorded"
stamp=$(stat -c %Y.%N "$work/build_info.hpp")
sleep 1.1
write
[ "$(stat -c %Y.%N "$work/build_info.hpp")" = "$stamp" ] || fail "unchanged commit rewrote the header"
echo two > "$repo/file"
write
grep -q "git_commit = \"$first-dirty\";" "$work/build_info.hpp" || fail "an edited tree is not marked dirty"
git -C "$repo" -c user.name=t -c user.email=t@t commit -q -am two
write
second=$(git -C "$repo" rev-parse --short=12 HEAD)
[ "$second" != "$first" ] || fail "test setup: no new commit"
grep -q "git_commit = \"$second\";" "$work/build_info.hpp" || fail "a new commit is not named without reconfiguring"
echo "build_info names $first, $first-dirty, $second as the tree changes"
