#!/usr/bin/env bash
# The third-party workflow, end to end: install the SDK, build the plain-C
# example plugin as a separate CMake project against it, check it with
# `arbor plugin-check`, load it through ARBOR_PLUGIN_PATH and run it.
#   example_out_of_tree.sh <build dir> <source dir> <arbor executable>
set -euo pipefail
build=$1 src=$2 arbor=$3
work=$build/tests/sdk/example-out-of-tree
rm -rf "$work" && mkdir -p "$work"

cmake --install "$build" --prefix "$work/prefix" --component sdk >/dev/null
test -f "$work/prefix/include/arbor/arbor.h"
test -f "$work/prefix/lib/cmake/ArborSDK/ArborSDKConfig.cmake"

cmake -S "$src/sdk/examples/window-filter" -B "$work/build" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/build" >/dev/null
lib=$work/build/window-filter.so
test -f "$lib"

# Only the entry symbol is exported.
exported=$(nm -D --defined-only "$lib" | awk '{print $3}' | grep -v '^_' | sort | tr '\n' ' ')
[ "$exported" = "arbor_entry " ] || { echo "exports more than arbor_entry: $exported"; exit 1; }

"$arbor" plugin-check "$lib"

export ARBOR_PLUGIN_PATH=$work/build
"$arbor" plugins --json > "$work/plugins.json"
grep -q '"id": "org.arbor.example.window"' "$work/plugins.json"

"$arbor" convert --phantom head --phantom-size 32 --filter org.arbor.example.window \
    --window.low 100 --window.high 500 -o "$work/windowed.nrrd"
"$arbor" info "$work/windowed.nrrd" --json > "$work/info.json"
/usr/bin/python3 - "$work/info.json" <<'PY'
import json, sys
info = json.load(open(sys.argv[1]))
lo, hi = info["stored"]["min"], info["stored"]["max"]
assert lo == 100 and hi == 500, f"window not applied: {lo}..{hi}"
print(f"windowed phantom spans {lo}..{hi}")
PY
echo "out-of-tree example plugin: built, checked, loaded and run"
