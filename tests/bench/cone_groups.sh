#!/usr/bin/env bash
# What a face hierarchy could spare the line drawings' passes over every face (mesh_lines.c). The
# facing and edge passes: tests/bench/cone_groups.py groups each mesh's faces G at a time, by
# position or by normal, and tests each group's normal cone against random orthographic views (the
# meshes' own geometry; no modelc code runs). The face pass's boxes: each mesh baked --as both and
# drawn over the benchmarks' turn (tests/bench/mesh_frames.c --near: the frame's line pixels before
# any is hidden, against the faces the face pass visits, one by one and in position groups), and
# which of those faces hide a line pixel at all (mesh_frames --hiders).
# Replaces its marked section of RESULTS.md (make bench-cones, and make bench, run it):
#   tests/bench/cone_groups.sh [RESULTS.md]
#   CONE_MODELS (bunny00 fandisk lion_head), CONE_DIRECTIONS (20), CONE_FRAMES (20: frames of the
#   turn for the face pass's table), CONE_HIDER_FRAMES (256: frames of the turn for the hiders'),
#   CONE_SIZE (320x240), CONE_GROUP_SIZES ("0 16 32 64 128": the bakes' --mesh-groups for the last
#   table, callgrind instructions of the lines style at each; 0: none)
set -euo pipefail
cd "$(dirname "$0")/../.."
. tests/lib.sh
. tests/bench/section.sh
results=${1:-tests/bench/RESULTS.md}
models=${CONE_MODELS:-bunny00 fandisk lion_head}
directions=${CONE_DIRECTIONS:-20} frames=${CONE_FRAMES:-20} size=${CONE_SIZE:-320x240}
hider_frames=${CONE_HIDER_FRAMES:-256} group_sizes=${CONE_GROUP_SIZES:-0 16 32 64 128}
out=build/bench/cone_groups
modelc=build/bin/modelc
[ -x "$modelc" ] || { echo "cone_groups.sh: $modelc missing: run make gen" >&2; exit 1; }
mkdir -p "$out"
cmds=()
run() { cmds+=("$*"); "$@"; }
cflags="-O2 -g -std=c99 -D_POSIX_C_SOURCE=200809L -Wall -Wextra -Iruntime/include -Iruntime/front/host -Iruntime/front/common"
: >"$out/rows.txt"
: >"$out/near.txt"
for m in $models; do
    f=$(model_file "$m")
    cmds+=("python3 tests/bench/cone_groups.py $f $directions 1 32 64 128")
    python3 tests/bench/cone_groups.py "$f" "$directions" 1 32 64 128 | sed "s/^/$m /" >>"$out/rows.txt"
    rm -rf "${out:?}/$m"
    run "$modelc" "$f" -o "$out" --name "$m" --depth 1 --as both -q
    # shellcheck disable=SC2086
    run gcc $cflags -DPM=mc_pmesh_$m -include "$out/$m/$m.h" -o "$out/$m-frames" tests/bench/mesh_frames.c \
        runtime/src/*.c runtime/front/common/mesh_frame.c "$out/$m"/*.c
    run "$out/$m-frames" --near "$frames" --size "$size" >"$out/$m.near.txt"
    run "$out/$m-frames" --hiders "$hider_frames" --size "$size" >"$out/$m.hiders.txt"
    echo "$m $out/$m.near.txt" >>"$out/near.txt"
done
# the face groups (--mesh-groups G): the lines style's instructions a frame at each group size, and
# the groups' own test (mesh_lines.c group_may_hide, with what it calls) a group
: >"$out/groups.txt"
for m in $models; do
    f=$(model_file "$m")
    for g in $group_sizes; do
        name=${m}_g$g
        rm -rf "${out:?}/$name"
        run "$modelc" "$f" -o "$out" --name "$name" --depth 1 --as both --mesh-groups "$g" -q
        # shellcheck disable=SC2086
        run gcc $cflags -DPM=mc_pmesh_$name -include "$out/$name/$name.h" -o "$out/$name-frames" tests/bench/mesh_frames.c \
            runtime/src/*.c runtime/front/common/mesh_frame.c "$out/$name"/*.c
        run valgrind --tool=callgrind --toggle-collect=mc_front_mesh_frame --callgrind-out-file="$out/$name.cg" \
            "$out/$name-frames" --style lines --frames "$frames" --size "$size" >/dev/null 2>"$out/$name.cg.log"
        total=$(sed -n 's/^summary: //p' "$out/$name.cg")
        tests=$(callgrind_annotate --inclusive=yes --threshold=100 "$out/$name.cg" 2>/dev/null |
            awk '/:group_may_hide/ { gsub(",", "", $1); if ($1 + 0 > best) best = $1 + 0 } END { print best + 0 }')
        faces=$(python3 -c "import json; print(json.load(open('$out/$name/budget.json'))['pmesh']['faces'])")
        echo "$m $g $total $tests $faces" >>"$out/groups.txt"
    done
done
cmds+=("callgrind_annotate --inclusive=yes --threshold=100 $out/NAME_gG.cg   # group_may_hide's inclusive count")
python3 - "$out/rows.txt" "$directions" "$out/near.txt" "$frames" "$size" "$hider_frames" "$out/groups.txt" >"$out/section.md" <<'PY'
import re, sys
rows = [l.split() for l in open(sys.argv[1])]
print("## Face groups and normal cones: what a hierarchy could spare a line drawing\n")
print("`tests/bench/cone_groups.sh` (`make bench-cones`): each mesh's faces (the catalogue's file, exact normals in "
      "doubles) grouped G at a time, by position (the Morton order of their centres) or by normal first (4 x 4 cells "
      "on each face of the cube of directions, then that order); each group's normal cone (the mean normal as its "
      f"axis, the widest angle to it) tested against {sys.argv[2]} random orthographic view directions. A group is "
      "front or back when its whole cone is, else mixed: its faces need their own facing test. A uniform group that "
      "shares an edge with a group of another class may hold silhouettes on that border; only the faces of a uniform "
      "group whose neighbours are all of its class could be passed over whole by the facing and edge passes. Shares "
      "of the faces, mean over the directions. bunny00 is a scan: its normals change from face to face, so its "
      "cones are wide. (An analysis of the geometry alone: no modelc code runs.)\n")
print("| mesh | grouping | G | groups | mixed | uniform at a border | could be passed over |")
print("|---|---|---:|---:|---:|---:|---:|")
for m, g, size, n, mixed, border, skip in rows:
    print(f"| {m} | {g} | {size} | {int(n):,} | {float(mixed) * 100:.1f} % | {float(border) * 100:.1f} % | {float(skip) * 100:.1f} % |")

def field(text, key):
    return float(re.search(r"^" + re.escape(key) + r" ([\d.]+)$", text, re.M).group(1))
print("\n### The face pass's boxes: line pixels near the faces\n")
print(f"The other pass over every face, the sparse way's face pass (mesh_lines.c `face_pass`), tests each face it "
      "visits (a closed part's front faces, else all) for a line pixel in its box of pixel centres, and only a face "
      "that has one is set up as a triangle. A hierarchy over the faces could pass over a group whose screen box holds "
      f"no line pixel. Measured on the benchmarks' turn ({sys.argv[4]} frames at {sys.argv[5]}, the full level, "
      "orthographic) with modelc's own frames (`tests/bench/mesh_frames.c --near`: each frame's line pixels before any "
      "is hidden, `mc_mesh_lines_sparse` with `MC_LINES_NO_HIDING`, against the cached projection): per frame, the "
      "faces the face pass visits; of those, the ones whose box meets a line pixel (at most what the face pass sets "
      "up: a line pixel an earlier face empties is gone when a later one comes); the ones with a line pixel within d pixels of their "
      "corners' pixels (d = 1, 2, 4, 8: what a test on a grid of such cells could not pass over); and the ones a "
      "hierarchy of position groups could pass over: the faces in the Morton order of their centres, G at a time, a "
      "group passed over when the box of its visited faces' pixels holds no line pixel. Shares of the faces visited, "
      "mean over the frames.\n")
print("| mesh | faces | visited | box meets a line pixel | within 1 px | within 2 px | within 4 px | within 8 px | "
      "passed over, groups of 32 | of 64 | of 128 |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for line in open(sys.argv[3]):
    m, path = line.split()
    t = open(path).read()
    faces = int(re.search(r"faces (\d+)", t).group(1))
    vis = field(t, "visited per frame")
    pct = lambda v: f"{100 * v / vis:.1f} %"
    cells = " | ".join(pct(field(t, f"within {d} per frame")) for d in (1, 2, 4, 8))
    groups = " | ".join(pct(field(t, f"spared in groups of {g} per frame")) for g in (32, 64, 128))
    print(f"| {m} | {faces:,} | {vis:,.0f} | {pct(field(t, 'meeting per frame'))} | {cells} | {groups} |")

hn = int(sys.argv[6])
step = 360 / hn
print("\n### The faces that hide a line pixel\n")
print(f"Of the faces the face pass visits, which ones empty an entry at all: the face pass done face by face in its "
      f"order over {hn} frames of the same turn ({step:.2f} degrees of yaw apart), at {sys.argv[5]} "
      "(`tests/bench/mesh_frames.c --hiders`: each frame's line pixels offered, none hidden, then every visited face's "
      "box test and `mc_raster_triangle_hide_box`). A face that empties one is a hider. Visiting only a frame's "
      "hiders, in the same order, leaves the same entries as the whole face pass (every other face emptied none "
      "and changed nothing a later one meets), and so does any set holding them; the run checks both, each frame "
      "with its own hiders and with the union of its 16-frame window's, against `mc_mesh_lines_sparse`'s own "
      "face pass, bit for bit. Ring 1: the faces with a corner at an end of an edge drawn in the frame; ring 2: "
      "those with a corner on a ring-1 face (where a line could be hidden by the faces around it, as at its own "
      "ends). Union over W frames: the faces that hide in any of W neighbouring frames of the turn (a set a "
      "precomputed table for that arc of yaw would have to hold at least; it grows as the frames are sampled "
      "closer, as the hiders change from one pixel rounding to the next). Line pixels: the buffer's entries "
      "(distinct pixels, where `mc_lines_stats.pixels` counts each line's). Means over the frames; shares of the "
      "faces visited, hiders in the rings as shares of the hiders.\n")
print(f"| mesh | visited | box meets a line pixel | hiders | line pixels | hidden | ring 1 / ring 2 | hiders in ring 1 / 2 "
      f"| union over 4 frames ({4 * step:.1f} deg) | 16 ({16 * step:.1f} deg) | 64 ({64 * step:.1f} deg) |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for line in open(sys.argv[3]):
    m, path = line.split()
    t = open(path.replace(".near.txt", ".hiders.txt")).read()
    vis = field(t, "visited per frame")
    hid = field(t, "hiders per frame")
    pct = lambda v: f"{100 * v / vis:.1f} %"
    hp = lambda v: f"{100 * v / hid:.1f} %" if hid else "-"
    unions = " | ".join(f"{field(t, f'union over {w} per window'):,.0f} ({pct(field(t, f'union over {w} per window'))})"
                        for w in (4, 16, 64))
    print(f"| {m} | {vis:,.0f} | {pct(field(t, 'meeting per frame'))} | {hid:,.1f} ({pct(hid)}) | "
          f"{field(t, 'line pixels offered per frame'):,.0f} | {field(t, 'line pixels hidden per frame'):,.0f} | "
          f"{pct(field(t, 'ring 1 per frame'))} / {pct(field(t, 'ring 2 per frame'))} | "
          f"{hp(field(t, 'hiders in ring 1 per frame'))} / {hp(field(t, 'hiders in ring 2 per frame'))} | {unions} |")

rows = [l.split() for l in open(sys.argv[7])]
print("\n### Face groups: the lines style at each group size\n")
print(f"Each mesh baked with `--mesh-groups G` (pmesh.h groups: the full mesh's faces G at a time in the Morton order of "
      "their centres, each group's box; 0: none) and drawn in the lines style (`mesh_frames --style lines`, "
      f"`mc_front_mesh_frame`, the vertex cache on) over {sys.argv[4]} frames of the same turn at {sys.argv[5]}: callgrind "
      "instructions a frame (`mc_front_mesh_frame` with everything it calls), and the groups' own tests "
      "(`group_may_hide`, inclusive: the box bound `mc_xform_box_bound` and the scan of the bounded pixels' entries, "
      "`mc_sdepth_any_from`) a frame and a group. The same drawings at every size (tests/gen/pmesh.sh checks them "
      "byte for byte against no groups).\n")
print("| mesh | G | groups | instructions a frame | against none | group tests a frame | a group |")
print("|---|---:|---:|---:|---:|---:|---:|")
frames = int(sys.argv[4])
none = {m: int(t) for m, g, t, _, _ in rows if g == "0"}
for m, g, total, tests, faces in rows:
    G, F, T = int(g), int(faces), int(total) / frames
    n = (F + G - 1) // G if G else 0
    ratio = f"{int(total) / none[m]:.3f}" if m in none else "-"
    per = f"{int(tests) / frames / n:.0f}" if n else "-"
    print(f"| {m} | {G} | {n:,} | {T / 1e6:.2f} M | {ratio} | {int(tests) / frames / 1e6:.2f} M | {per} |")
PY
write_section "$results" cone_groups "$out/section.md" "${cmds[@]}"
