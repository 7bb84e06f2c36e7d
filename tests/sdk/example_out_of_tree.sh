#!/usr/bin/env bash
# The third-party workflow, end to end, for every example the SDK installs:
# install the SDK, build each plain-C example in share/arbor/sdk/examples as
# a separate CMake project against it, check it with `arbor plugin-check`,
# then load them all through ARBOR_PLUGIN_PATH and use each in a real command
# whose output is checked against an independent oracle
# (example_runs.py).
#   example_out_of_tree.sh <build dir> <source dir> <arbor executable>
set -euo pipefail
build=$1 src=$2 arbor=$3
work=$build/tests/sdk/example-out-of-tree
rm -rf "$work" && mkdir -p "$work"

cmake --install "$build" --prefix "$work/prefix" --component sdk >/dev/null
prefix=$work/prefix
test -f "$prefix/include/arbor/arbor.h"
test -f "$prefix/include/arbor/param_check.h"
test -f "$prefix/lib/cmake/ArborSDK/ArborSDKConfig.cmake"
test -f "$prefix/share/arbor/sdk/docs/plugin-guide.md"
test -f "$prefix/share/arbor/sdk/docs/contract.md"

# Every file the guide and the contract name must be in the installed SDK.
/usr/bin/python3 "$src/tests/sdk/doc_references.py" "$prefix"

examples=(window-filter pgm-stack-importer persistence-volume-simplifier lineage-depictor palette-generator
          mip-renderer)
installed=$(cd "$prefix/share/arbor/sdk/examples" && ls -d */ | tr -d / | sort | tr '\n' ' ')
expected=$(printf '%s\n' "${examples[@]}" | sort | tr '\n' ' ')
[ "$installed" = "$expected" ] || { echo "installed examples: $installed; tested: $expected"; exit 1; }

mkdir -p "$work/plugins"
for example in "${examples[@]}"; do
  cmake -S "$prefix/share/arbor/sdk/examples/$example" -B "$work/build/$example" -DCMAKE_BUILD_TYPE=Release \
        -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_COMPILE_WARNING_AS_ERROR=ON >/dev/null
  cmake --build "$work/build/$example" >/dev/null
  lib=$(ls "$work/build/$example"/*.so)
  # Only the entry symbol is exported.
  exported=$(nm -D --defined-only "$lib" | awk '{print $3}' | grep -v '^_' | sort | tr '\n' ' ')
  [ "$exported" = "arbor_entry " ] || { echo "$example exports more than arbor_entry: $exported"; exit 1; }
  "$arbor" plugin-check "$lib" >"$work/$example.check.txt" 2>&1 ||
    { cat "$work/$example.check.txt"; echo "$example fails plugin-check"; exit 1; }
  cp "$lib" "$work/plugins/"
done

export ARBOR_PLUGIN_PATH=$work/plugins
"$arbor" plugins --json > "$work/plugins.json"
for id in window pgm-stack persistence-volume lineage palette mip; do
  grep -q "\"id\": \"org.arbor.example.$id\"" "$work/plugins.json" || { echo "org.arbor.example.$id not loaded"; exit 1; }
done

/usr/bin/python3 "$src/tests/sdk/example_runs.py" "$arbor" "$work/runs"
echo "out-of-tree example plugins: built, checked, loaded and run"
