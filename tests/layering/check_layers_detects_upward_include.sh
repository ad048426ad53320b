#!/usr/bin/env bash
# The layering check must fail on an include that points upward and on one without a folder,
# and pass on the same tree without them. Works on a copy; the source tree is not touched.
set -eu
src_root=$1
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cp -r "$src_root/src" "$src_root/stages" "$scratch/"
check="$src_root/tools/check-layers.sh"

"$check" "$scratch" > "$scratch/clean.log" || { echo "FAIL: clean copy rejected"; cat "$scratch/clean.log"; exit 1; }

# model/ (low) including stages/ (high).
printf '#include "stages/relax_stage.hpp"\n' >> "$scratch/src/model/state.hpp"
if "$check" "$scratch" > "$scratch/bad.log"; then echo "FAIL: upward include accepted"; exit 1; fi
grep -q 'src/model/state.hpp:.*layer model includes higher layer stages' "$scratch/bad.log" ||
  { echo "FAIL: message does not name the file and layers:"; cat "$scratch/bad.log"; exit 1; }

# An include without its folder.
cp "$src_root/src/model/state.hpp" "$scratch/src/model/state.hpp"
printf '#include "vec3.hpp"\n' >> "$scratch/src/forces/gravity.hpp"
if "$check" "$scratch" > "$scratch/bad2.log"; then echo "FAIL: include without folder accepted"; exit 1; fi
grep -q 'names no layer folder' "$scratch/bad2.log" || { echo "FAIL:"; cat "$scratch/bad2.log"; exit 1; }
echo "layering check rejects upward and folderless includes"
