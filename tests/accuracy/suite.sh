#!/usr/bin/env bash
# The mesh reference renderer (runtime/ref/mesh_ref.c) against synthetic meshes with known images and
# against the octree of bunny00 (tests/accuracy/meshref_test.c says what and why). About 20 s.
set -u
cd "$(dirname "$0")/../.."
out=build/tests/accuracy
mkdir -p "$out"
MODELC=${MODELC:-build/bin/modelc}
[ -x "$MODELC" ] || { echo "not ok - accuracy: $MODELC missing (make gen)"; exit 1; }
[ -f build/models/bunny00.off ] || make -s build/models/bunny00.off >/dev/null 2>&1 || {
    echo "not ok - accuracy: build/models/bunny00.off missing (make models)"; exit 1; }
# the catalogue's bake of bunny00 (depth 8), with the original mesh dumped for the reference
rm -rf "$out/acc_bunny00"
if ! "$MODELC" build/models/bunny00.off -o "$out" --name acc_bunny00 --depth 8 -q \
    --dump-reference "$out/bunny00.ref" >"$out/bake.log" 2>&1; then
    echo "not ok - accuracy: bake with --dump-reference failed: $(head -n 2 "$out/bake.log" | tr '\n' ' ')"; exit 1
fi
echo "ok - modelc --dump-reference writes the reference dump"
if ! gcc -std=c99 -O2 -g -Wall -Wextra -Werror -Iruntime/include -Iruntime/ref -o "$out/meshref_test" \
    tests/accuracy/meshref_test.c runtime/ref/mesh_ref.c runtime/src/*.c "$out/acc_bunny00"/acc_bunny00_data_*.c \
    "$out/acc_bunny00/acc_bunny00_scene.c" -lm 2>"$out/build.log"; then
    echo "not ok - accuracy: test build failed: $(head -n 3 "$out/build.log" | tr '\n' ' ')"; exit 1
fi
"$out/meshref_test" "$out/bunny00.ref"
