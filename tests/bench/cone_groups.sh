#!/usr/bin/env bash
# What a face hierarchy could spare the line drawings' passes over every face (the facing pass and
# the edge pass, mesh_lines.c): tests/bench/cone_groups.py groups each mesh's faces G at a time, by
# position or by normal, and tests each group's normal cone against random orthographic views.
# Analysis of the meshes' own geometry (no modelc code runs): why the lines style visits every face.
# Replaces its marked section of RESULTS.md (make bench-cones, and make bench, run it):
#   tests/bench/cone_groups.sh [RESULTS.md]
set -euo pipefail
cd "$(dirname "$0")/../.."
. tests/lib.sh
. tests/bench/section.sh
results=${1:-tests/bench/RESULTS.md}
models=${CONE_MODELS:-bunny00 fandisk lion_head}
directions=${CONE_DIRECTIONS:-20}
out=build/bench/cone_groups
mkdir -p "$out"
cmds=()
: >"$out/rows.txt"
for m in $models; do
    f=$(model_file "$m")
    cmds+=("python3 tests/bench/cone_groups.py $f $directions 1 32 64 128")
    python3 tests/bench/cone_groups.py "$f" "$directions" 1 32 64 128 | sed "s/^/$m /" >>"$out/rows.txt"
done
python3 - "$out/rows.txt" "$directions" >"$out/section.md" <<'PY'
import sys
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
PY
write_section "$results" cone_groups "$out/section.md" "${cmds[@]}"
