#!/usr/bin/env bash
# The mesh reference renderer (runtime/ref/mesh_ref.c) against synthetic meshes with known images and
# against the octrees of bunny00 and kitten (tests/accuracy/meshref_test.c says what and why). About 20 s.
set -u
cd "$(dirname "$0")/../.."
out=build/tests/accuracy
mkdir -p "$out"
. tests/lib.sh
MODELC=${MODELC:-build/bin/modelc}
[ -x "$MODELC" ] || { echo "not ok - accuracy: $MODELC missing (make gen)"; exit 1; }
for f in bunny00.off kitten.xyz; do
    [ -f build/models/$f ] || make -s build/models/$f >/dev/null 2>&1 || {
        echo "not ok - accuracy: build/models/$f missing (make models)"; exit 1; }
done
# the catalogue's bake of bunny00 (depth 8), with the original mesh dumped for the reference
rm -rf "$out/acc_bunny00"
if ! "$MODELC" build/models/bunny00.off -o "$out" --name acc_bunny00 --depth 8 -q \
    --dump-reference "$out/bunny00.ref" >"$out/bake.log" 2>&1; then
    echo "not ok - accuracy: bake with --dump-reference failed: $(head -n 2 "$out/bake.log" | tr '\n' ' ')"; exit 1
fi
# the catalogue's kitten (point set, depth 7)
rm -rf "$out/acc_kitten"
if ! "$MODELC" build/models/kitten.xyz -o "$out" --name acc_kitten --depth 7 -q \
    --dump-reference "$out/kitten.ref" >>"$out/bake.log" 2>&1; then
    echo "not ok - accuracy: point-set bake with --dump-reference failed: $(tail -n 2 "$out/bake.log" | tr '\n' ' ')"; exit 1
fi
echo "ok - modelc --dump-reference writes the reference dumps (mesh, point set)"
if ! gcc -std=c99 -O2 -g -Wall -Wextra -Werror -Iruntime/include -Iruntime/ref -o "$out/meshref_test" \
    tests/accuracy/meshref_test.c runtime/ref/mesh_ref.c runtime/ref/ref.c $(rt_objs | tr '\n' ' ') "$out/acc_bunny00"/acc_bunny00_data_*.c \
    "$out/acc_bunny00/acc_bunny00_octree.c" "$out/acc_kitten"/acc_kitten_data_*.c "$out/acc_kitten/acc_kitten_octree.c" -lm 2>"$out/build.log"; then
    echo "not ok - accuracy: test build failed: $(head -n 3 "$out/build.log" | tr '\n' ' ')"; exit 1
fi
"$out/meshref_test" "$out/bunny00.ref" "$out/kitten.ref"
