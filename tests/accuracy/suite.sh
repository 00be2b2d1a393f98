#!/usr/bin/env bash
# The mesh reference renderer (runtime/ref/mesh_ref.c) against synthetic meshes with known images and
# against the octrees of bunny00 and kitten (tests/accuracy/meshref_test.c says what and why); and
# make bench-accuracy's program (acc.c) built and run with and without a level-selection bound. About 30 s.
set -u
cd "$(dirname "$0")/../.."
out=build/tests/accuracy
mkdir -p "$out"
. tests/lib.sh
check() { check_problems "$@"; }
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
st=$?

# the benchmark's program (make bench-accuracy: tests/accuracy/acc.c) builds against the runtime and its
# level-selection bound (--error PX, mc_octree_options.max_error) draws the level the bound asks for: at
# depth 8 and 320x240 a 2-pixel bound draws level 7 at zoom 1 (a node spans 240 / 128 pixels) and the
# bake's level 8 at zoom 1.5 and 2, so the zoom-1 frames lose PSNR and the others are the same frames
if gcc -std=c99 -O2 -Wall -Wextra -Werror -Iruntime/include -Iruntime/ref -Iruntime/front/host \
    -DACC_SCENE=mc_octree_acc_bunny00 -o "$out/acc" tests/accuracy/acc.c runtime/ref/mesh_ref.c runtime/ref/ref.c \
    $(rt_objs | tr '\n' ' ') "$out/acc_bunny00"/acc_bunny00_data_*.c "$out/acc_bunny00/acc_bunny00_octree.c" -lm \
    2>"$out/acc-build.log"; then
    ok "acc.c (make bench-accuracy's program) builds against the runtime"
    "$out/acc" "$out/bunny00.ref" --tag off --frames 1 >"$out/acc-off.csv" 2>"$out/acc-off.log"
    a=$?
    "$out/acc" "$out/bunny00.ref" --tag e2 --frames 1 --error 2 >"$out/acc-e2.csv" 2>"$out/acc-e2.log"
    b=$?
    check "acc.c --error 2 (a 2-pixel level-selection bound) at depth 8: a coarser level at zoom 1, the bake's level at zoom 1.5 and 2" \
        "$([ $a -eq 0 ] && [ $b -eq 0 ] || echo "exit $a and $b: $(cat "$out/acc-off.log" "$out/acc-e2.log" | oneline)")$(
        python3 - "$out/acc-off.csv" "$out/acc-e2.csv" <<'EOF'
import csv, sys
cols = "tag yaw pitch zoom splat fill psnr ssim coverage ms cpu_ms status".split()
off, e2 = ({tuple(r[1:6]): r for r in csv.reader(open(f))} for f in sys.argv[1:3])
why = []
if len(off) != 72 or set(off) != set(e2): why.append(f"{len(off)} and {len(e2)} rows")
for k in sorted(set(off) & set(e2)):
    if off[k][11] != "ok" or e2[k][11] != "ok": why.append(f"{k} status {off[k][11]} {e2[k][11]}"); continue
    p0, p2 = float(off[k][6]), float(e2[k][6])
    if float(k[2]) == 1 and not p2 < p0 - 0.1: why.append(f"{k}: PSNR {p2} with the bound, {p0} without")
    if float(k[2]) > 1 and p2 != p0: why.append(f"{k}: PSNR {p2} with the bound, {p0} without (same level)")
print("; ".join(why[:4]))
EOF
)"
else
    notok "acc.c (make bench-accuracy's program) builds against the runtime" "$(head -n 3 "$out/acc-build.log" | oneline)"
fi
[ $st -eq 0 ] || exit $st
exit $status
