#!/usr/bin/env bash
# The progressive mesh's level changes and size, side by side with OpenMesh in one run: the same
# decimation of each mesh (quadric error, no normal flips, to the end) baked by modelc --as both and
# recorded by OpenMesh's ModProgMeshT as its .pm file; then, per round, a full refinement from the
# base and a full coarsening back by modelc's mc_pmesh_lod_set (tests/bench/pmesh_lod.c) and by
# OpenMesh's vertex_split / collapse on its half-edge mesh as its ProgViewer does
# (tests/bench/openmesh_pm.cpp): ns per level change, median over rounds, and the ratio in each
# round; callgrind instructions per level change for modelc; flash bytes per split against the .pm
# file's. Then the same mesh as a stream (--emit stream, depth 1 so that the octree is negligible),
# plain and with --stream-splits packed, each read whole by mc_stream_feed (tests/bench/stream_decode.c,
# alternately, per round) and the levels of the arrays it filled swept as the bake's: bytes per split,
# read time per split, callgrind instructions per split of the packed decoder. Writes (in place) a
# marked section of RESULTS.md.
#   tests/bench/pmesh.sh [RESULTS.md]        (make bench runs it; make bench-pmesh alone)
#   PMESH_MODELS ("bunny00 fandisk lion_head"), PMESH_ROUNDS (7)
set -euo pipefail
cd "$(dirname "$0")/../.."
. tests/bench/section.sh
. tests/lib.sh   # model_file
results=${1:-tests/bench/RESULTS.md}
models=${PMESH_MODELS:-bunny00 fandisk lion_head} rounds=${PMESH_ROUNDS:-7}
out=build/bench/pmesh
mkdir -p "$out"
cmds=()
run() { cmds+=("$*"); "$@"; }
run g++ -O2 -std=c++17 -o "$out/openmesh_pm" tests/bench/openmesh_pm.cpp -lOpenMeshTools -lOpenMeshCore
: >"$out/rows.txt"
for m in $models; do
    src=$(model_file "$m") || { echo "pmesh.sh: $m: no such catalogue model, or it cannot be extracted" >&2; exit 1; }
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
# the streams: plain and packed splits, read whole
run gcc -O2 -g -std=c99 -D_POSIX_C_SOURCE=200809L -Wall -Wextra -Iruntime/include -o "$out/stream_decode" \
    tests/bench/stream_decode.c runtime/src/*.c
cap() { python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['stream']['buffer'])" "$1"; }
for m in $models; do
    for mode in plain packed; do
        run build/bin/modelc "$(model_file "$m")" -o "$out" --name "${m}_$mode" --depth 1 --as both --emit stream \
            --stream-splits "$mode" -q
    done
    run valgrind --tool=callgrind --toggle-collect=mc_stream_packed_splits --callgrind-out-file="$out/$m.packed.cg" \
        "$out/stream_decode" "$out/${m}_packed/${m}_packed.mcs" "$(cap "$out/${m}_packed/budget.json")" --feeds 1 \
        >"$out/$m.packed.cg.txt" 2>"$out/$m.packed.cg.log"
    for mode in plain packed; do
        "$out/stream_decode" "$out/${m}_$mode/${m}_$mode.mcs" "$(cap "$out/${m}_$mode/budget.json")" 0 >"$out/$m.$mode.txt"
    done
    : >"$out/$m.stream.times"
    for r in $(seq 1 "$rounds"); do
        line=""
        for mode in plain packed; do
            line+=" $("$out/stream_decode" "$out/${m}_$mode/${m}_$mode.mcs" "$(cap "$out/${m}_$mode/budget.json")" 1 |
                sed -n 's/^ns per [a-z ]* //p' | tr '\n' ' ')"
        done
        echo "$line" >>"$out/$m.stream.times"
    done
done
cmds+=("$out/stream_decode $out/NAME_MODE/NAME_MODE.mcs BUFFER 1   # per round, plain then packed, $rounds rounds")
load=$(cut -d' ' -f1-3 /proc/loadavg)
python3 - "$out" "$rounds" "$load" >"$out/section.md" <<'PY'
import json, re, statistics, sys
out, rounds, load = sys.argv[1:4]
print("## Progressive mesh: level changes, flash and stream bytes per split\n")
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
print("The same mesh as a stream (`--emit stream --as both --depth 1`), its splits plain (version 2: a split's vertex, "
      "face count, position, parent, subtree size and faces' corners, 25 bytes a split) and packed (`--stream-splits packed`, version 3, runtime/include/modelc/stream.h: "
      "the split vertex implied by the depth-first order, each new face's third corner a rank among the parent's "
      "neighbours, each corner an offset in its vertex's subtree, positions Exp-Golomb coded as differences to the "
      "mean of the new vertex's neighbours; the adjacency the edge order alone, the opposites found by the reader). "
      "The reader decodes the packed splits into the same arrays as the plain "
      "ones (tests/stream/suite.sh checks them byte for byte against the bake), keeping the level's mesh in the "
      "receive buffer while it does (`MC_STREAM_PACKED_BYTES`: 24 B a face and 12 B a vertex more). Bytes per split: "
      "the base and split records, framing included, over the splits; the adjacency's record likewise. Read: `mc_stream_feed` of the whole file in "
      "one piece, every record checked (CRC-32 included) and, once the adjacency is in, the face bits worked out (`mc_mesh_face_bits`: the bake's stored shades and crease bits), over the splits (tests/bench/stream_decode.c; per round "
      "plain then packed, median over rounds). Level change: `mc_pmesh_lod_set` from the base to the full level "
      "and back on the arrays the stream filled. Ir: callgrind, `mc_stream_packed_splits` only, per split.\n")
print("| mesh | plain B per split | packed B per split | .pm B per split | adjacency B per split, plain / packed | "
      "plain read ns per split | packed read ns per split | packed stream read, splits per s | packed decoder Ir per split | "
      "level change ns (packed stream's arrays) | buffer plain | buffer packed |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
per_round = []
for m in open(f"{out}/rows.txt").read().split():
    head = {}
    for mode in ("plain", "packed"):
        f = open(f"{out}/{m}.{mode}.txt").read().split()
        head[mode] = (int(f[3]), int(f[6]), int(f[9]))   # splits, mesh bytes, adjacency bytes
    rows = [list(map(float, l.split())) for l in open(f"{out}/{m}.stream.times")]
    med = [statistics.median(r[k] for r in rows) for k in range(4)]
    refs = int(re.search(r"refs:\s+([\d,]+)", open(f"{out}/{m}.packed.cg.log").read()).group(1).replace(",", ""))
    pm = int(re.search(r"pm bytes (\d+)", open(f"{out}/{m}.om.txt").read()).group(1))
    S = head["packed"][0]
    buf = {mode: json.load(open(f"{out}/{m}_{mode}/budget.json"))["stream"]["buffer"] for mode in ("plain", "packed")}
    print(f"| {m} | {head['plain'][1] / S:.2f} | {head['packed'][1] / S:.2f} | {pm / S:.2f} | "
          f"{head['plain'][2] / S:.2f} / {head['packed'][2] / S:.2f} | {med[0]:.0f} | {med[2]:.0f} | "
          f"{1e9 / med[2] / 1e6:.2f} M | {refs / S:.0f} | {med[3]:.2f} | {buf['plain']:,} B | {buf['packed']:,} B |")
    per_round.append(f"{m}: " + ", ".join(f"{r[0]:.0f} / {r[2]:.0f}" for r in rows))
print()
print("Per round (plain / packed read ns per split): " + "; ".join(per_round) + ".")
print()
print(f"Load average at the end: {load}.")
PY
write_section "$results" pmesh "$out/section.md" "${cmds[@]}"
