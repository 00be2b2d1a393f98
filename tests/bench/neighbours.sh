#!/usr/bin/env bash
# Line drawings at coarse levels with and without the level's neighbour table (--mesh-neighbours,
# pmesh.h mc_pmesh_lod_neighbours), side by side: tests/bench/mesh_frames.c --style lines (the lines
# style's frame, mc_front_mesh_frame with the sparse depth buffer) at levels from 2 % of the vertices
# to the full mesh, each level timed without and with the table in turn (the order swapped every
# round), ROUNDS rounds of a full turn; callgrind's instructions a frame for both at each level; and
# what the table costs a level change (tests/bench/pmesh_lod.c: refinement from the base to the
# full level and back, without and with it); then what a level change of S splits costs the line
# drawings' crease bits (mesh_frames --step: brought over from the last level, against every edge
# tested). Writes a marked section of RESULTS.md.
#   tests/bench/neighbours.sh [RESULTS.md]        (make bench runs it; make bench-neighbours alone)
#   NBR_MODEL (bunny00), NBR_SHARES ("0.02 0.05 0.1 0.2 0.33 0.5 1": shares of the vertices),
#   NBR_ROUNDS (7), NBR_FRAMES (100 a timed turn), NBR_STEPS ("10 100 1000": splits a change),
#   NBR_CREASE_MODELS ("bunny00 fandisk lion_head": the meshes of the crease-bit table)
set -euo pipefail
cd "$(dirname "$0")/../.."
. tests/bench/section.sh
results=${1:-tests/bench/RESULTS.md}
model=${NBR_MODEL:-bunny00} rounds=${NBR_ROUNDS:-7} frames=${NBR_FRAMES:-100}
shares=${NBR_SHARES:-0.02 0.05 0.1 0.2 0.33 0.5 1} steps=${NBR_STEPS:-10 100 1000}
out=build/bench/neighbours
mkdir -p "$out"
cmds=()
run() { cmds+=("$*"); "$@"; }
src=build/models/$model.off
[ -f "$src" ] || make -s "$src"
rm -rf "${out:?}/$model"
run build/bin/modelc "$src" -o "$out" --name "$model" --depth 1 --as both -q
cflags="-O2 -g -std=c99 -D_POSIX_C_SOURCE=200809L -Wall -Wextra -Iruntime/include -Iruntime/front/host -Iruntime/front/common"
# shellcheck disable=SC2086
run gcc $cflags -DPM=mc_pmesh_$model -include "$out/$model/$model.h" -o "$out/frames" tests/bench/mesh_frames.c \
    runtime/src/*.c runtime/front/common/mesh_frame.c "$out/$model"/*.c
# shellcheck disable=SC2086
run gcc $cflags -DPM=mc_pmesh_$model -include "$out/$model/$model.h" -o "$out/lod" tests/bench/pmesh_lod.c \
    runtime/src/pmesh.c "$out/$model"/*.c
V=$(python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['pmesh']['vertices'])" "$out/$model/budget.json")
levels=""
for s in $shares; do levels+=" $(python3 -c "print(max(1, round($s * $V)))")"; done
flag_of() { [ "$1" != table ] || echo --neighbours; }   # plain: none; table: the level's neighbour table
: >"$out/times.txt"
for r in $(seq 1 "$rounds"); do
    for n in $levels; do
        if [ $((r % 2)) = 1 ]; then order="plain table"; else order="table plain"; fi
        for w in $order; do
            # shellcheck disable=SC2046
            "$out/frames" --style lines --vertices "$n" --time "$frames" $(flag_of "$w") >"$out/$n-$w.txt"
            ms=$(sed -n 's/^ms per frame (median) //p' "$out/$n-$w.txt")
            echo "$n $w $r $ms" >>"$out/times.txt"
        done
    done
done
cmds+=("$out/frames --style lines --vertices N --time $frames [--neighbours]   # per level, $rounds rounds, the order swapped every round")
for n in $levels; do
    for w in plain table; do
        # shellcheck disable=SC2046
        valgrind --tool=callgrind --toggle-collect=mc_front_mesh_frame --callgrind-out-file="$out/$n-$w.cg" \
            "$out/frames" --style lines --vertices "$n" --frames 20 $(flag_of "$w") >/dev/null 2>"$out/$n-$w.cg.log"
    done
done
cmds+=("valgrind --tool=callgrind --toggle-collect=mc_front_mesh_frame --callgrind-out-file=$out/N-W.cg $out/frames --style lines --vertices N --frames 20 [--neighbours]")
for r in $(seq 1 "$rounds"); do
    "$out/lod" 1 | sed -n 's/^ns per level change /plain /p' >>"$out/lod.txt.$$"
    "$out/lod" --neighbours 1 | sed -n 's/^ns per level change /table /p' >>"$out/lod.txt.$$"
done
mv "$out/lod.txt.$$" "$out/lod.txt"
cmds+=("$out/lod 1; $out/lod --neighbours 1   # $rounds rounds")
# the crease bits after a level change of S splits (mesh_frames --step): the first frame's level has
# them from the warm-up (every edge taken), each of the next 20 brings them over from the last; on
# each of the meshes of bench-mesh, at its full level and at a fifth of its vertices
crease_models=${NBR_CREASE_MODELS:-bunny00 fandisk lion_head}
: >"$out/crease-runs.txt"
for m in $crease_models; do
    bin=$out/frames
    if [ "$m" != "$model" ]; then
        msrc=build/models/${m//_/-}.off   # (the catalogue's file: lion_head is lion-head.off)
        [ -f "$msrc" ] || make -s "$msrc"
        rm -rf "${out:?}/$m"
        run build/bin/modelc "$msrc" -o "$out" --name "$m" --depth 1 --as both -q
        bin=$out/frames-$m
        # shellcheck disable=SC2086
        run gcc $cflags -DPM=mc_pmesh_$m -include "$out/$m/$m.h" -o "$bin" tests/bench/mesh_frames.c \
            runtime/src/*.c runtime/front/common/mesh_frame.c "$out/$m"/*.c
    fi
    mV=$(python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['pmesh']['vertices'])" "$out/$m/budget.json")
    for n in $mV $(python3 -c "print(round(0.2 * $mV))"); do
        for st in $steps; do
            for k in 1 21; do
                valgrind --tool=callgrind --toggle-collect=mc_mesh_creases_update --callgrind-out-file="$out/crease-$m-$n-$st-$k.cg" \
                    "$bin" --style lines --vertices "$n" --step "$st" --frames "$k" --size 64x48 \
                    >"$out/crease-$m-$n-$st-$k.txt" 2>"$out/crease-$m-$n-$st-$k.log"
            done
            # every edge taken at the other level of the pair (mesh_frames --step's: S splits finer, or coarser
            # past the full mesh), where half the changes land
            other=$((n + st <= mV ? n + st : n - st))
            valgrind --tool=callgrind --toggle-collect=mc_mesh_creases_update --callgrind-out-file="$out/crease-$m-$n-$st-other.cg" \
                "$bin" --style lines --vertices "$other" --frames 1 --size 64x48 \
                >"$out/crease-$m-$n-$st-other.txt" 2>"$out/crease-$m-$n-$st-other.log"
            echo "$m $n $st $other" >>"$out/crease-runs.txt"
        done
    done
done
cmds+=("valgrind --tool=callgrind --toggle-collect=mc_mesh_creases_update --callgrind-out-file=$out/crease-M-N-S-K.cg $out/frames[-M] --style lines --vertices N --step S --frames K --size 64x48   # K = 1, 21; frames-M: built as frames, for mesh M")
cmds+=("valgrind --tool=callgrind --toggle-collect=mc_mesh_creases_update --callgrind-out-file=$out/crease-M-N-S-other.cg $out/frames[-M] --style lines --vertices N2 --frames 1 --size 64x48   # N2 = N + S, or N - S past the full mesh")
load=$(cut -d' ' -f1-3 /proc/loadavg)
python3 - "$out" "$model" "$V" "$frames" "$rounds" "$load" >"$out/section.md" <<'PY'
import re, statistics, sys
out, model, V, frames, rounds, load = sys.argv[1:7]
V = int(V)
t = {}
for line in open(f"{out}/times.txt"):
    n, w, r, ms = line.split()
    t.setdefault((int(n), w), []).append(float(ms))
def ir(n, w):
    s = open(f"{out}/{n}-{w}.cg").read()
    return int(re.search(r"^summary: (\d+)", s, re.M).group(1)) / 20
print("## Line drawings at coarse levels: the neighbour table\n")
print(f"`tests/bench/neighbours.sh` (`make bench`, `make bench-neighbours`): {model} baked `--as both`, the lines "
      "style's frame (`mc_front_mesh_frame`, sparse depth buffer, vertex cache) at 320x240 over a full turn of "
      f"{frames} frames (`tests/bench/mesh_frames.c --style lines --vertices N`), at each level without and with the "
      "level's neighbour table (`--neighbours`: `mc_pmesh_lod_neighbours`, what a bake with `--mesh-neighbours` gives "
      "the viewer). Without it a face's neighbour across an edge is the stored full-mesh neighbour, walked across the "
      "faces the level lacks (`mc_pmesh_lod_opposite`); with it, a table the level changes keep. ms: median over "
      f"{rounds} rounds of each run's median frame, both ways timed one after the other in every round (the order "
      "swapped each round); ratio: median over rounds of without / with. Instructions: callgrind, "
      "`mc_front_mesh_frame` only, 20 frames.\n")
print("| level (vertices) | share | lines a frame | ms without | ms with | ratio | Ir a frame without | Ir a frame with |")
print("|---:|---:|---:|---:|---:|---:|---:|---:|")
for n in sorted({k[0] for k in t}):
    a, b = t[(n, "plain")], t[(n, "table")]
    ratio = statistics.median(x / y for x, y in zip(a, b))
    said = [open(f"{out}/{n}-{w}.txt").read() for w in ("plain", "table")]
    total = [re.search(r"^lines total (\d+)", s, re.M).group(1) for s in said]
    if total[0] != total[1]: sys.exit(f"level {n}: {total[0]} lines without the table, {total[1]} with it")
    lines = float(re.search(r"^lines per frame ([\d.]+)", said[0], re.M).group(1))
    print(f"| {n:,} | {n / V:.0%} | {lines:,.0f} | {statistics.median(a):.3f} | {statistics.median(b):.3f} | {ratio:.2f}x | "
          f"{ir(n, 'plain') / 1e6:.2f} M | {ir(n, 'table') / 1e6:.2f} M |")
lod = {"plain": [], "table": []}
for line in open(f"{out}/lod.txt"):
    w, ns = line.split()
    lod[w].append(float(ns))
p, q = statistics.median(lod["plain"]), statistics.median(lod["table"])
print(f"\nA level change (`tests/bench/pmesh_lod.c`: the base to the full level and back, split by split), median of "
      f"{rounds} rounds: {p:.1f} ns without the table, {q:.1f} ns with it ({q / p:.1f} times: each split or collapse "
      "keeps the table: a split walks its new faces' edges from their stored neighbours and gives the faces it finds "
      "their new neighbour, a collapse pairs the faces across each removed face; {:.1f} M and {:.1f} M level changes a "
      "second).".format(1e3 / p, 1e3 / q))
print("\n### The crease bits after a level change\n")
print("The line drawings keep each level's crease bits (`mc_mesh_lines`' memory, mesh_lines.h) and, when the level "
      "changed by under a 16th of its faces, bring them over from the last one by testing only the faces around the "
      "vertices the splits between moved; else every edge is taken again (an edge between two faces the level has as "
      "the full mesh has them, across the stored neighbour, from the bake's stored bits, pmesh.h face_bits; any other "
      "from its faces' normals; at the full level every bit is the stored one, read in order, and only a change of "
      "under a 256th of the faces is brought over to it). Instructions of `mc_mesh_creases_update` "
      "(callgrind `--toggle-collect=mc_mesh_creases_update`): `mesh_frames --style lines --vertices N --step S` at 64x48, "
      "whose first frame's bits come from the warm-up frame (every edge taken) and whose next 20 frames alternate "
      "between the level and the one S splits finer (coarser at the full level): a change = (the run of "
      "21 frames - the run of 1) / 20, against every edge taken at either level of the pair (the run of 1 at each, "
      "their mean: what the change would cost without bringing the bits over). The thresholds (16, 256) were set on "
      "bunny00; the other meshes show whether they hold there too: up to them a change brought over should cost less "
      "than every edge (times fewer above 1; a 16th of the faces is some 470 splits at a fifth of bunny00's vertices; "
      "a change over its threshold takes every edge, about 1).\n")
print("| mesh | level (vertices) | faces | splits changed | share of the faces | Ir, every edge taken (this level, the other) | Ir a change | times fewer |")
print("|---|---:|---:|---:|---:|---:|---:|---:|")
def summary(m, n, st, k):
    return int(re.search(r"^summary: (\d+)", open(f"{out}/crease-{m}-{n}-{st}-{k}.cg").read(), re.M).group(1))
for line in open(f"{out}/crease-runs.txt"):
    m, n, st, other = line.split()
    faces = int(re.search(r"^faces per frame (\d+)", open(f"{out}/crease-{m}-{n}-{st}-1.txt").read(), re.M).group(1))
    full = summary(m, n, st, 1)
    full2 = summary(m, n, st, "other")
    per = (summary(m, n, st, 21) - full) / 20
    print(f"| {m} | {int(n):,} | {faces:,} | {st} | 1/{faces / (2 * int(st)):.0f} | {full / 1e6:.2f} M, "
          f"{full2 / 1e6:.2f} M | {per / 1e6:.2f} M | {(full + full2) / 2 / per:.1f} |")
print(f"\nLoad average at the end: {load}.")
PY
write_section "$results" neighbours "$out/section.md" "${cmds[@]}"
