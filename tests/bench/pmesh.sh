#!/usr/bin/env bash
# The progressive mesh's level changes and size, side by side with OpenMesh in one run: the same
# decimation of each mesh (quadric error, no normal flips, to the end) baked by modelc --as both and
# recorded by OpenMesh's ModProgMeshT as its .pm file; then, per round, a full refinement from the
# base and a full coarsening back by modelc's mc_pmesh_lod_set (tests/bench/pmesh_lod.c) and by
# OpenMesh's vertex_split / collapse on its half-edge mesh as its ProgViewer does
# (tests/bench/openmesh_pm.cpp): ns per level change, median over rounds, and the ratio in each
# round; callgrind instructions per level change for modelc; flash bytes per split against the .pm
# file's. Appends (replacing an earlier copy) a marked section to RESULTS.md.
#   tests/bench/pmesh.sh [RESULTS.md]        (make bench runs it; make bench-pmesh alone)
#   PMESH_MODELS ("bunny00 fandisk"), PMESH_ROUNDS (7)
set -euo pipefail
cd "$(dirname "$0")/../.."
. tests/bench/section.sh
results=${1:-tests/bench/RESULTS.md}
models=${PMESH_MODELS:-bunny00 fandisk} rounds=${PMESH_ROUNDS:-7}
out=build/bench/pmesh
mkdir -p "$out"
cmds=()
run() { cmds+=("$*"); "$@"; }
run g++ -O2 -std=c++17 -o "$out/openmesh_pm" tests/bench/openmesh_pm.cpp -lOpenMeshTools -lOpenMeshCore
: >"$out/rows.txt"
for m in $models; do
    src=build/models/$m.off
    [ -f "$src" ] || make -s "$src"
    run build/bin/modelc "$src" -o "$out" --name "$m" --depth 5 --as both -q
    run gcc -O2 -g -std=c99 -D_POSIX_C_SOURCE=200809L -Wall -Wextra -Iruntime/include "-DPM=mc_pmesh_$m" \
        -include "$out/$m/$m.h" -o "$out/$m-lod" tests/bench/pmesh_lod.c runtime/src/pmesh.c "$out/$m"/*.c
    run valgrind --tool=callgrind --toggle-collect=mc_pmesh_lod_set --callgrind-out-file="$out/$m.cg" \
        "$out/$m-lod" --sweeps 3 >"$out/$m.cg.txt" 2>"$out/$m.cg.log"
    "$out/$m-lod" 1 >"$out/$m.lod.txt"
    run "$out/openmesh_pm" "$src" "$out/$m.pm" 1 >"$out/$m.om.txt"
    : >"$out/$m.times"
    for r in $(seq 1 "$rounds"); do
        a=$("$out/$m-lod" 1 | sed -n 's/^ns per level change //p')
        b=$("$out/openmesh_pm" --read "$out/$m.pm" 1 | sed -n 's/^ns per level change //p')
        echo "$a $b" >>"$out/$m.times"
    done
    echo "$m" >>"$out/rows.txt"
done
cmds+=("$out/NAME-lod 1; $out/openmesh_pm --read $out/NAME.pm 1   # per round, $rounds rounds")
# what the same records would take coded by variable-length fields read in split order
for m in $models; do run python3 tests/bench/pmesh_bits.py "$out" "$m" >"$out/$m.bits.txt"; done
load=$(cut -d' ' -f1-3 /proc/loadavg)
python3 - "$out" "$rounds" "$load" >"$out/section.md" <<'PY'
import json, re, statistics, sys
out, rounds, load = sys.argv[1:4]
print("## Progressive mesh: level changes and flash per split\n")
print("`tests/bench/pmesh.sh` (`make bench`, `make bench-pmesh`): each mesh decimated to the end by modelc `--as both` "
      "and by OpenMesh's own ModProgMeshT with the same modules (quadric error, normal-flip guard); per round, a full "
      "refinement from the base mesh and a full coarsening back: modelc's `mc_pmesh_lod_set` on the baked arrays "
      "(tests/bench/pmesh_lod.c) and OpenMesh's `vertex_split` / `collapse` on its half-edge mesh read from its .pm file, "
      f"as its ProgViewer app does (tests/bench/openmesh_pm.cpp); wall clock, gcc -O2, {rounds} rounds, median over rounds, "
      "ratio = median over rounds of OpenMesh's time / modelc's in the same round. Instructions: callgrind, "
      "`mc_pmesh_lod_set` only, three sweeps. Flash: the bake's mesh arrays (budget.json `pmesh.bytes`) against the .pm "
      "file (float positions, 32-bit indices, connectivity rebuilt in RAM).\n")
print("| mesh | faces | splits | modelc ns per change | OpenMesh ns per change | ratio | modelc Ir per change | "
      "ancestor entries per split | modelc flash B per split | .pm B per split | modelc LOD RAM |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
per_round = []
for m in open(f"{out}/rows.txt").read().split():
    b = json.load(open(f"{out}/{m}/budget.json"))["pmesh"]
    rows = [list(map(float, l.split())) for l in open(f"{out}/{m}.times")]
    a = statistics.median(r[0] for r in rows)
    o = statistics.median(r[1] for r in rows)
    ratio = statistics.median(r[1] / r[0] for r in rows)
    refs = int(re.search(r"refs:\s+([\d,]+)", open(f"{out}/{m}.cg.log").read()).group(1).replace(",", ""))
    changes = float(re.search(r"level changes (\d+)", open(f"{out}/{m}.cg.txt").read()).group(1))
    sub = float(re.search(r"mean subtree size ([\d.]+)", open(f"{out}/{m}.lod.txt").read()).group(1))
    pm = int(re.search(r"pm bytes (\d+)", open(f"{out}/{m}.om.txt").read()).group(1))
    print(f"| {m} | {b['faces']:,} | {b['splits']:,} | {a:.2f} | {o:.1f} | {ratio:.0f}x | {refs / changes:.1f} | {sub:.2f} | "
          f"{b['bytes'] / b['splits']:.2f} | {pm / b['splits']:.2f} | {b['lod_ram']:,} B |")
    per_round.append(f"{m}: " + ", ".join(f"{r[0]:.2f} / {r[1]:.1f}" for r in rows))
print()
print("Per round (modelc / OpenMesh ns): " + "; ".join(per_round) + ".")
print()
print("The flash per split against a sequential coding: `tests/bench/pmesh_bits.py` reads each bake's arrays back and "
      "counts what its records would take as variable-length fields decoded in split order (a measure, not a format: "
      "such a stream could not be read at random, so the faces and positions of the level drawn would have to be "
      "decoded into RAM). Corners: at its split's level each corner of a new face is the split vertex, its parent or a "
      "third vertex x, and the full mesh's corner an offset in that vertex's subtree; parent and subtree size Elias "
      "gamma; positions the Elias-gamma difference to the parent's. Below that, a decoder that also keeps the level's "
      "mesh, each vertex's faces, as it goes (a half-edge mesh in RAM, as OpenMesh's): x as a rank among the parent's "
      "neighbours, the position from the mean of the new vertex's neighbours.\n")
print("```")
for m in open(f"{out}/rows.txt").read().split():
    print(open(f"{out}/{m}.bits.txt").read().rstrip())
print("```")
print(f"Load average at the end: {load}.")
PY
write_section "$results" pmesh "$out/section.md" "${cmds[@]}"
