#!/usr/bin/env bash
# The progressive-mesh part (--as both; gen/pmesh.cpp, runtime/src/pmesh.c) on catalogue meshes and
# on shapes made here that no catalogue model has: an open grid (borders), a thin two-sided sheet,
# many components, non-manifold edges and vertices, repeated corners, zero-area faces and coincident
# vertices. For each bake, tests/gen/pmesh_check.c, built with the runtime's pmesh.c and the bake:
#   - every level (or 800 of them, shuffled): every face present has three distinct corners present
#     at that level, F(n) faces, and the arrays' tree and split invariants hold;
#   - at chosen levels the faces equal, as a set of oriented triangles of quantized positions, those
#     OpenMesh's Decimater itself leaves at that many vertices (modelc --dump-pmesh-level);
#   - mc_mesh_render's images (flat-shaded, z-buffered) equal a composition of the tested parts in
#     doubles (pmesh_check.c render), orthographic and perspective, culled and not, and with the eye
#     inside the model, where faces through the near plane are clipped (against an exact clipping in
#     doubles);
#   - the line drawings: every edge's kind (silhouette, crease, border) as a double-precision
#     classification of the level's faces gives it, and the lines drawn as those edges' lines (clipped
#     at the near plane with the eye inside);
#   - every eighth checked level: each face's neighbours equal a search of the level's faces;
#   - for the made shapes and a grid of 67,600 vertices (4-byte indices), the stream with packed splits
#     (--stream-splits packed): the arrays its reader decodes equal its plain stream's
#     (tests/stream/stream_same.c), also with every third corner found by the decoder's passes;
#   - silhouettes (tests/gen/sil_check.c): the exact scan equals the line drawing's classification, the
#     bounded search lists only silhouettes, each once, within its budget, the same on every run and
#     with the vertex cache (mc_sil_cache), also where the near plane flags corners;
# and budget.json's figures add up. Then: a point set asked for a mesh fails with one line and no
# output; --max-faces caps the finest level; a points-only bake is unchanged by the mesh code.
#
# usage: tests/gen/pmesh.sh [MODELC]        (default build/bin/modelc)
set -u
cd "$(dirname "$0")/../.."
modelc=${1:-build/bin/modelc}
TAP_PREFIX="pmesh: "
. tests/lib.sh
temp_dir
out=$tmp/out
rt=$(rt_objs | tr '\n' ' ')   # the runtime as the viewers have it
# and with the line drawings' other form of their coin-toss tests (config.h MC_MESH_SELECT: the
# default's values on x86-64, branches elsewhere), which must draw the same
mesh_select_alt=$(printf '#include "modelc/config.h"\nMC_MESH_SELECT\n' | gcc -E -P -Iruntime/include - | tail -n 1)
mesh_select_alt=$((1 - mesh_select_alt))
gcc -O2 -std=c99 -ffreestanding -Wall -Wextra -Werror -Iruntime/include -ffunction-sections -fdata-sections \
    -DMC_MESH_SELECT=$mesh_select_alt -c -o "$tmp/mesh_lines_alt.o" runtime/src/mesh_lines.c ||
    { notok "runtime/src/mesh_lines.c compiles with MC_MESH_SELECT=$mesh_select_alt" ""; exit 1; }
rt_alt="$(tr ' ' '\n' <<<"$rt" | grep -v '/mesh_lines\.o$' | tr '\n' ' ') $tmp/mesh_lines_alt.o"
# the double-precision references the checker links, compiled once (the same for every bake)
ref_objs=""
for f in raster_ref xform_ref; do
    gcc -std=c99 -O2 -Wall -Wextra -Werror -Iruntime/include -c -o "$tmp/$f.o" "runtime/ref/$f.c" 2>"$tmp/$f.cc" ||
        { notok "runtime/ref/$f.c compiles" "$(head -n 3 "$tmp/$f.cc" | oneline)"; exit 1; }
    ref_objs+=" $tmp/$f.o"
done

# canon FILE: the faces of a dump, each rotated to start at its smallest corner (orientation kept),
# sorted: two dumps of the same oriented faces give the same text
canon() {
    awk '{ a = $1" "$2" "$3; b = $4" "$5" "$6; c = $7" "$8" "$9
           if (a <= b && a <= c) print a" | "b" | "c; else if (b <= c) print b" | "c" | "a; else print c" | "a" | "b }' \
        "$1" | LC_ALL=C sort
}

# bake_check LABEL FILE [OPTIONS...]: bakes FILE --as both, builds the checker, runs its level
# checks; sets $bake (the output directory) and $checker; fails the check and returns 1 on any problem
bake_check() {
    local label=$1 file=$2 name
    shift 2
    name=$(echo "$label" | tr -c 'a-z0-9\n' '_')
    bake=$out/$name
    rm -rf "$bake"
    # with dump_level set, the bake also writes OpenMesh's decimation to that many vertices
    # (--dump-pmesh-level, which leaves the bake as it is), so that same_as_openmesh does not bake
    # the same file with the same options again for it
    local dump=()
    [ -z "${dump_level:-}" ] || dump=(--dump-pmesh-level "$dump_level:$tmp/openmesh-$name-$dump_level.txt")
    if ! "$modelc" "$file" -o "$out" --name "$name" --depth 5 --as both -q "$@" "${dump[@]}" >"$tmp/$name.log" 2>&1; then
        notok "$label: bakes --as both $*" "$(oneline <"$tmp/$name.log")"
        return 1
    fi
    checker=$tmp/check_$name
    # the bake's files compiled once, for both checkers
    local bobjs=$tmp/objs-$name
    mkdir -p "$bobjs"
    # shellcheck disable=SC2086
    if ! (cd "$bobjs" && gcc -std=c99 -O2 -Wall -Wextra -Werror -I"$OLDPWD/runtime/include" -c "$bake"/*.c) \
        >"$tmp/$name.cc" 2>&1 ||
        ! gcc -std=c99 -O2 -Wall -Wextra -Werror -Iruntime/include "-DPM=mc_pmesh_$name" -include "$bake/$name.h" \
            -o "$checker" tests/gen/pmesh_check.c $ref_objs $rt "$bobjs"/*.o -lm >>"$tmp/$name.cc" 2>&1; then
        notok "$label: the bake compiles with the runtime (-Wall -Wextra -Werror)" "$(head -n 3 "$tmp/$name.cc" | oneline)"
        return 1
    fi
    # shellcheck disable=SC2086
    if ! gcc -std=c99 -O2 -Wall -Wextra -Werror -Iruntime/include "-DPM=mc_pmesh_$name" -include "$bake/$name.h" \
        -o "$checker-alt" tests/gen/pmesh_check.c $ref_objs $rt_alt "$bobjs"/*.o -lm >"$tmp/$name.alt.cc" 2>&1; then
        notok "$label: the checker compiles with MC_MESH_SELECT=$mesh_select_alt" "$(head -n 3 "$tmp/$name.alt.cc" | oneline)"
        return 1
    fi
    if ! gcc -std=c99 -O2 -Wall -Wextra -Werror -Iruntime/include "-DPM=mc_pmesh_$name" -include "$bake/$name.h" \
        -o "$checker-sil" tests/gen/sil_check.c $rt "$bobjs"/*.o -lm >"$tmp/$name.sil.cc" 2>&1; then
        notok "$label: the silhouette checker compiles" "$(head -n 3 "$tmp/$name.sil.cc" | oneline)"
        return 1
    fi
    local r
    r=$("$checker" levels 2>&1)
    if [[ $r == ok:* ]]; then ok "$label: levels: ${r#ok: }"; else notok "$label: levels" "$r"; return 1; fi
}

# renders LABEL N...: mc_mesh_render at each level N against the reference composition
# (pmesh_check.c render): orthographic front, turned with back faces culled, perspective with the
# eye outside the model, and with the eye inside it (faces through the near plane clipped); for the
# catalogue's closed meshes also inside and culled (clipped faces culled by their planes: an open
# shape seen so may show no face at all)
renders() {
    local label=$1 n view r d views
    local -A said   # the default's words for each line-drawing view of the level
    shift
    views=("96 72 0 0 0 0 65536 131072 0" "96 72 0 700 -300 200 98304 131072 1" "80 60 1 -1100 250 0 65536 131072 1"
        "80 60 1 2048 100 0 65536 16384 0")
    case $label in bunny00 | fandisk) views+=("80 60 1 2048 100 0 65536 16384 1") ;; esac
    for n in "$@"; do
        for view in "${views[@]}"; do
            r=$("$checker" render "$n" $view 2>&1)
            if [[ $r == ok:* ]]; then ok "$label: mc_mesh_render, view ($view): ${r#ok: }"
            else notok "$label: mc_mesh_render, view ($view)" "${r#not ok: }"; fi
        done
        # line drawings (pmesh_check.c lines): the edges' kinds against the reference's, the lines
        # drawn as their edges' mc_line, hidden ones a subset; frontal, turned and magnified, perspective,
        # and with the eye inside (lines clipped at the near plane)
        for view in "160 120 0 0 0 0 65536 131072" "160 120 0 700 -300 200 262144 131072" \
            "120 90 1 -1100 250 0 65536 131072" "120 90 1 2048 100 0 65536 16384"; do
            r=$("$checker" lines "$n" $view 2>&1)
            said["$view"]=$r
            if [[ $r == ok:* ]]; then ok "$label: mc_mesh_lines, view ($view): ${r#ok: }"
            else notok "$label: mc_mesh_lines, view ($view)" "${r#not ok: }"; fi
        done
        # the other form (MC_MESH_SELECT): the same checks, and the same words as the default's
        for view in "160 120 0 700 -300 200 262144 131072" "120 90 1 -1100 250 0 65536 131072"; do
            r=$("$checker-alt" lines "$n" $view 2>&1)
            d=${said["$view"]}
            if [[ $r == ok:* ]] && [ "$r" = "$d" ]; then
                ok "$label: mc_mesh_lines with MC_MESH_SELECT=$mesh_select_alt, view ($view): as the default"
            elif [[ $r == ok:* ]]; then
                notok "$label: mc_mesh_lines with MC_MESH_SELECT=$mesh_select_alt, view ($view)" "${r#ok: }; the default: ${d#ok: }"
            else notok "$label: mc_mesh_lines with MC_MESH_SELECT=$mesh_select_alt, view ($view)" "${r#not ok: }"; fi
        done
    done
    # silhouettes, exact and searched (sil_check.c check)
    r=$("$checker-sil" check 160 120 2>&1)
    if [[ $r == ok:* ]]; then ok "$label: silhouettes: ${r#ok: }"; else notok "$label: silhouettes" "${r#not ok: }"; fi
}

# same_as_openmesh LABEL FILE N [OPTIONS...]: level N of the bake equals OpenMesh's decimation to N
same_as_openmesh() {
    local label=$1 file=$2 n=$3 name
    shift 3
    name=$(echo "$label" | tr -c 'a-z0-9\n' '_')
    if [ -s "$tmp/openmesh-$name-$n.txt" ]; then
        # dumped by bake_check's bake of the same file with the same options (the same label)
        cp "$tmp/openmesh-$name-$n.txt" "$tmp/openmesh.txt"
    elif ! "$modelc" "$file" -o "$tmp/dump" --name "$name" --depth 5 --as both -q "$@" \
        --dump-pmesh-level "$n:$tmp/openmesh.txt" >"$tmp/dump.log" 2>&1; then
        notok "$label: level $n equals OpenMesh's decimation" "modelc: $(oneline <"$tmp/dump.log")"
        return
    fi
    "$checker" faces "$n" >"$tmp/runtime.txt"
    local a b
    a=$(canon "$tmp/openmesh.txt" | md5sum)
    b=$(canon "$tmp/runtime.txt" | md5sum)
    if [ ! -s "$tmp/openmesh.txt" ]; then notok "$label: level $n equals OpenMesh's decimation" "OpenMesh left no faces"
    elif [ "$a" = "$b" ]; then ok "$label: level $n: its $(wc -l <"$tmp/runtime.txt") faces equal OpenMesh's decimation to $n vertices"
    else notok "$label: level $n equals OpenMesh's decimation" \
        "$(diff <(canon "$tmp/openmesh.txt") <(canon "$tmp/runtime.txt") | grep -c '^[<>]') faces differ"; fi
}

# budget_adds_up LABEL: budget.json's mesh figures (the mesh, its face bits, its line arrays, its face
# groups) agree with the arrays it lists
budget_adds_up() {
    local label=$1 problems
    problems=$(python3 - "$bake/budget.json" <<'PY'
import json, sys
b = json.load(open(sys.argv[1]))
pm, arrays = b["pmesh"], b["flash"]["arrays"]
lines = sum(v for k, v in arrays.items() if "_pm_opposite" in k or "_pm_edge_order" in k)
faceb = sum(v for k, v in arrays.items() if "_pm_face_bits" in k)
groups = sum(v for k, v in arrays.items() if "_pm_group" in k)
mesh = sum(v for k, v in arrays.items() if "_pm_" in k) - lines - faceb - groups
ib, V, F, S, E, hb = pm["index_bytes"], pm["vertices"], pm["faces"], pm["splits"], pm["edges"], pm["half_edge_bytes"]
per = 1 << pm["record_shift"]   # the split faces' bits: a chunk's splits in (per + 7) // 8 bytes
bits = S // per * ((per + 7) // 8) + (S % per + 7) // 8
want = V * 6 + V * ib + S * ib + bits + F * 3 * ib + 3 * 36   # the arrays; the palette: 32 greys, 4 line colours
p = []
if mesh != pm["bytes"] or mesh != want: p.append(f"mesh arrays {mesh} bytes, budget says {pm['bytes']}, layout gives {want}")
if faceb != pm["face_bytes"] or faceb != F: p.append(f"face bits {faceb} bytes, budget says {pm['face_bytes']}, faces {F}")
if lines != pm["line_bytes"] or lines != F * 3 * hb + E * hb:
    p.append(f"line arrays {lines} bytes, budget says {pm['line_bytes']}, layout gives {F * 3 * hb + E * hb}")
G = pm["group_size"]   # face groups (--mesh-groups): a box of 12 bytes a group, a face's index a face
want_groups = (F + G - 1) // G * 12 + F * (2 if F <= 65536 else 3) if G else 0
if groups != pm["group_bytes"] or groups != want_groups:
    p.append(f"face groups {groups} bytes, budget says {pm['group_bytes']}, layout gives {want_groups}")
if hb != (2 if 4 * F + 3 < 65535 else 4): p.append(f"half_edge_bytes {hb} for {F} faces")
if b["flash"]["total"] != sum(arrays.values()): p.append(f"flash total {b['flash']['total']} != arrays {sum(arrays.values())}")
if pm["lod_ram"] != V * ib or b["ram"]["pmesh_lod"] != V * ib: p.append("lod_ram is not vertices x index_bytes")
if S != V - pm["base_vertices"]: p.append("splits != vertices - base_vertices")
if ib != (2 if V <= 65535 else 4): p.append(f"index_bytes {ib} for {V} vertices")
if "pmesh" not in b["modules"]: p.append("modules lack pmesh")
print("; ".join(p))
PY
)
    check_problems "$label: budget.json's mesh figures add up (arrays, flash total, LOD RAM, modules)" "$problems"
}

# ---- catalogue meshes --------------------------------------------------------------------------
for m in bunny00 fandisk; do
    src=$(model_file "$m") || { notok "$m: model file" "cannot extract it (make models)"; continue; }
    case $m in
        bunny00) levels="100 2000" ;;
        fandisk) levels="500" ;;
    esac
    # bunny00 with face groups (pmesh.h groups: the line drawings' face pass by groups, checked against
    # the same drawing without them), fandisk without
    groups=()
    [ "$m" = bunny00 ] && groups=(--mesh-groups 32)
    dump_level=${levels%% *} bake_check "$m" "$src" "${groups[@]}" || continue
    budget_adds_up "$m"
    for n in $levels; do same_as_openmesh "$m" "$src" "$n"; done
    V=$(python3 -c "import json; print(json.load(open('$bake/budget.json'))['pmesh']['vertices'])")
    renders "$m" 300 "$V"
done

# ---- shapes made here --------------------------------------------------------------------------
python3 - "$tmp" <<'PY'
import math, sys
d = sys.argv[1]
def off(name, verts, faces):
    with open(f"{d}/{name}.off", "w") as f:
        f.write(f"OFF\n{len(verts)} {len(faces)} 0\n")
        for v in verts: f.write("%.9g %.9g %.9g\n" % v)
        for t in faces: f.write("3 %d %d %d\n" % t)
def grid(n, z=0.0, flip=False, base=0, wave=0.1):
    v = [(i / n, j / n, z + wave * math.sin(3 * i / n) * math.cos(2 * j / n)) for j in range(n + 1) for i in range(n + 1)]
    f = []
    for j in range(n):
        for i in range(n):
            a = base + j * (n + 1) + i; b = a + 1; c = a + n + 1; e = c + 1
            f += [(a, c, b), (b, c, e)] if flip else [(a, b, c), (b, e, c)]
    return v, f
# an open surface: borders everywhere around
v, f = grid(30); off("open_grid", v, f)
# a thin sheet: two grids 1e-3 apart, facing away from each other, stitched along the rim
v1, f1 = grid(20, 0.0, False); v2, f2 = grid(20, 1e-3, True, base=len(v1))
off("thin_sheet", v1 + v2, f1 + f2)
# many components: 40 tetrahedra in a row
v, f = [], []
for k in range(40):
    b = len(v); x = k * 0.05
    v += [(x, 0, 0), (x + 0.03, 0, 0), (x, 0.03, 0), (x, 0, 0.03)]
    f += [(b, b + 2, b + 1), (b, b + 1, b + 3), (b, b + 3, b + 2), (b + 1, b + 2, b + 3)]
off("components", v, f)
# non-manifold: three fins on one edge, and two cones touching at one vertex (bowtie), on a grid
v, f = grid(12)
n = len(v)
v += [(0.5, 0.5, 0.3), (0.5, 0.5, -0.3), (0.3, 0.7, 0.0)]
e0, e1 = 6 * 13 + 6, 6 * 13 + 7          # an interior grid edge
f += [(e0, e1, n), (e1, e0, n + 1), (e0, e1, n + 2)]
off("non_manifold", v, f)
# degenerate: a face with a repeated corner, zero-area faces (collinear corners), coincident vertices
v, f = grid(10)
n = len(v)
v += [(2, 0, 0), (2.5, 0, 0), (3, 0, 0), (0, 0, 0)]       # collinear three, and a copy of vertex 0
f += [(n, n + 1, n + 2), (n, n + 2, n + 1), (0, 0, 5), (n + 3, 1, 11)]
off("degenerate", v, f)
# more vertices than 16-bit indices hold (index_bytes 4): a 259 x 259 grid, 67,600 vertices
off("big_grid", *grid(259))
PY
# packed LABEL FILE: the shape as a stream with packed splits (stream.h version 3) and as a plain one
# (version 2, whose reader copies the records; tests/stream/suite.sh checks those against the bake):
# the arrays the reader fills from each are the same bytes (tests/stream/stream_same.c)
# (and again with the decoder's short sorted ring list of one entry, MC_STREAM_RING_LIST=1, so that every
# third corner goes through the passes it takes for rings longer than the list)
rt_passes="$(tr ' ' '\n' <<<"$rt" | grep -v '/stream_packed\.o$' | tr '\n' ' ') $tmp/stream_packed_passes.o"
# shellcheck disable=SC2086
{ gcc -std=c99 -O2 -Wall -Wextra -Werror -Iruntime/include -o "$tmp/stream_same" tests/stream/stream_same.c $rt &&
    gcc -std=c99 -O2 -ffreestanding -Wall -Wextra -Werror -Iruntime/include -DMC_STREAM_RING_LIST=1 -c \
        -o "$tmp/stream_packed_passes.o" runtime/src/stream_packed.c &&
    gcc -std=c99 -O2 -Wall -Wextra -Werror -Iruntime/include -o "$tmp/stream_same_passes" tests/stream/stream_same.c \
        $rt_passes; } >"$tmp/same.cc" 2>&1 || notok "tests/stream/stream_same.c builds" "$(oneline <"$tmp/same.cc")"
packed() {
    local label=$1 file=$2 name mode r cap
    name=$(echo "$label" | tr -c 'a-z0-9\n' '_')
    for mode in plain packed; do
        rm -rf "${out:?}/${name}_$mode"
        if ! "$modelc" "$file" -o "$out" --name "${name}_$mode" --depth 1 --as both --emit stream --stream-splits $mode -q \
            >"$tmp/${name}_$mode.log" 2>&1; then
            notok "$label: bakes --emit stream --stream-splits $mode" "$(oneline <"$tmp/${name}_$mode.log")"
            return 1
        fi
    done
    cap=$(python3 -c "import json, sys; print(max(json.load(open(f))['stream']['buffer'] for f in sys.argv[1:]))" \
        "$out/${name}_plain/budget.json" "$out/${name}_packed/budget.json")
    local same
    for same in stream_same stream_same_passes; do
        r=$("$tmp/$same" "$out/${name}_plain/${name}_plain.mcs" "$out/${name}_packed/${name}_packed.mcs" "$cap" 2>&1)
        if [[ $r == "ok same: versions 2 and 3,"* ]]; then ok "$label: packed splits ($same): ${r#ok same: }"
        else notok "$label: packed splits ($same)" "$r"; fi
    done
}

for s in open_grid thin_sheet components non_manifold degenerate; do
    groups=()
    case $s in open_grid | components) groups=(--mesh-groups 8) ;; esac
    bake_check "$s" "$tmp/$s.off" "${groups[@]}" || continue
    budget_adds_up "$s"
    V=$(python3 -c "import json; print(json.load(open('$bake/budget.json'))['pmesh']['vertices'])")
    V0=$(python3 -c "import json; print(json.load(open('$bake/budget.json'))['pmesh']['base_vertices'])")
    for n in $(printf '%s\n' "$V0" $(((V0 + V) / 2)) "$V" | uniq); do same_as_openmesh "$s" "$tmp/$s.off" "$n"; done
    renders "$s" "$V"
    packed "$s" "$tmp/$s.off"
done
# an open shape's streams said to be closed (the mesh record's flag set, every CRC made valid): the
# reader refuses the first border (the line drawings read a closed part's neighbours without asking)
for mode in plain packed; do
    f=$out/open_grid_$mode/open_grid_$mode.mcs
    [ -f "$f" ] || { notok "open_grid: a $mode stream said to be closed is refused" "no stream $f"; continue; }
    python3 - "$f" "$tmp/closed_$mode.mcs" <<'PY'
import struct, sys, zlib
b = bytearray(open(sys.argv[1], "rb").read())
at, found = 20, 0   # the header (MC_STREAM_HEADER_BYTES), then records: u8 kind, u8 level, u16 0, u32 n, payload, CRC-32
while at + 8 <= len(b):
    kind, n = b[at], struct.unpack_from("<I", b, at + 4)[0]
    if kind == 4:   # the mesh record (stream_mesh.h MC_STREAM_KIND_MESH): byte 22 of its payload, closed
        assert b[at + 8 + 22] == 0
        b[at + 8 + 22] = 1
        struct.pack_into("<I", b, at + 8 + n, zlib.crc32(bytes(b[at:at + 8 + n])))
        found = 1
    at += 12 + n
assert found
open(sys.argv[2], "wb").write(bytes(b))
PY
    cap=$(python3 -c "import json; print(json.load(open('$out/open_grid_$mode/budget.json'))['stream']['buffer'])")
    r=$("$tmp/stream_same" "$tmp/closed_$mode.mcs" "$tmp/closed_$mode.mcs" "$cap" 2>&1)
    if [[ $r == "FAIL $tmp/closed_$mode.mcs: mesh at byte "* ]]; then ok "open_grid: a $mode stream said to be closed is refused: ${r#FAIL $tmp/}"
    else notok "open_grid: a $mode stream said to be closed is refused" "$r"; fi
done
# the packed stream's 4-byte indices
packed big_grid "$tmp/big_grid.off" &&
    check_problems "big_grid: 67,600 vertices, so 4-byte indices in the packed stream's decoder" \
        "$(python3 -c "import json; p=json.load(open('$out/big_grid_packed/budget.json'))['pmesh']; print('' if (p['vertices'], p['index_bytes']) == (67600, 4) else p)")"
# what the input had, as budget.json reports it
inputs() { python3 -c "import json; i=json.load(open('$out/$1/budget.json'))['pmesh']['input']; print(i['$2'])"; }
r=$(python3 -c "import json; print(json.load(open('$out/degenerate/budget.json'))['pmesh']['faces'])" 2>&1)
check_problems "degenerate: the 200 grid faces, both zero-area faces and the face on a coincident vertex are in the mesh; the face with a repeated corner is not (the reader drops it)" \
    "$([ "$r" = 203 ] || echo "$r faces, want 203")"
r=$(inputs non_manifold vertex_copies_for_non_manifold_faces 2>&1)
check_problems "non_manifold: each of the three fins on an edge that already has two faces gets its own vertex copies, counted (budget.json)" \
    "$([ "$r" = 9 ] || echo "vertex_copies_for_non_manifold_faces: $r, want 9")"
r=$(python3 -c "import json; print(json.load(open('$out/components/budget.json'))['pmesh']['base_vertices'])" 2>&1)
check_problems "components: every one of the 40 tetrahedra keeps at least one vertex in the base mesh" \
    "$([ "$r" -ge 40 ] 2>/dev/null || echo "base_vertices: $r")"

# ---- --max-faces ---------------------------------------------------------------------------------
src=$(model_file bunny00)
# (bunny00 is closed, of genus 0: 10000 faces have 5002 vertices, the level same_as_openmesh checks
# below, so the bake dumps OpenMesh's decimation at it; at another finest level it bakes its own dump)
if dump_level=5002 bake_check "bunny00 --max-faces 10000" "$src" --max-faces 10000; then
    r=$(python3 -c "import json; p=json.load(open('$bake/budget.json'))['pmesh']; print(p['faces'], p['vertices'])")
    read -r F V <<<"$r"
    check_problems "bunny00 --max-faces 10000: the finest level has 9999 or 10000 faces" \
        "$([ "$F" -le 10000 ] && [ "$F" -ge 9999 ] || echo "$F faces")"
    same_as_openmesh "bunny00 --max-faces 10000" "$src" "$V" --max-faces 10000
fi

# ---- a point set ---------------------------------------------------------------------------------
src=$(model_file kitten)
rm -rf "$out/kitten"
"$modelc" "$src" -o "$out" --name kitten --as both -q >"$tmp/kitten.out" 2>&1
rc=$?
lines=$(wc -l <"$tmp/kitten.out")
problems=""
[ "$rc" = 1 ] || problems+="exit status $rc; "
[ "$lines" = 1 ] || problems+="$lines lines of output; "
grep -q "^modelc: $src: a point set cannot be baked as a mesh" "$tmp/kitten.out" || problems+="said: $(oneline <"$tmp/kitten.out"); "
[ -e "$out/kitten" ] && problems+="wrote $out/kitten; "
check_problems "kitten (a point set) --as both: one modelc: line, exit 1, no output" "$problems"

# ---- --mesh-neighbours without a place for the table: one line, exit 2, no output ----------------
src=$(model_file fandisk)
for args in "--as points" "--as both --emit lib"; do
    rm -rf "$out/nbr"
    # shellcheck disable=SC2086
    "$modelc" "$src" -o "$out" --name nbr --depth 1 $args --mesh-neighbours -q >"$tmp/nbr.out" 2>&1
    rc=$?
    problems=""
    [ "$rc" = 2 ] || problems+="exit status $rc; "
    [ "$(wc -l <"$tmp/nbr.out")" = 1 ] || problems+="$(wc -l <"$tmp/nbr.out") lines of output; "
    grep -q "^modelc: --mesh-neighbours: " "$tmp/nbr.out" || problems+="said: $(oneline <"$tmp/nbr.out"); "
    [ -e "$out/nbr" ] && problems+="wrote $out/nbr; "
    check_problems "fandisk $args --mesh-neighbours: one modelc: line, exit 2, no output" "$problems"
done

# ---- --mesh-groups that cannot be: one line, no output ------------------------------------------
for args in "--as both --mesh-groups 3" "--as points --mesh-groups 8" "--as both --emit stream --mesh-groups 8" \
    "--as both --chunk-bytes 256 --mesh-groups 1024"; do
    rm -rf "$out/grp"
    # shellcheck disable=SC2086
    "$modelc" "$src" -o "$out" --name grp --depth 1 $args -q >"$tmp/grp.out" 2>&1
    rc=$?
    problems=""
    [ "$rc" = 0 ] && problems+="exit status 0; "
    [ "$(wc -l <"$tmp/grp.out")" = 1 ] || problems+="$(wc -l <"$tmp/grp.out") lines of output; "
    grep -q "^modelc: .*--mesh-groups[ :]" "$tmp/grp.out" || problems+="said: $(oneline <"$tmp/grp.out"); "
    [ -e "$out/grp" ] && problems+="wrote $out/grp; "
    check_problems "fandisk $args: one modelc: line, a non-zero exit, no output" "$problems"
done

# ---- the arrays' layout: a bake states it, and a runtime that reads another stops the build ----------
problems=""
pmc="$out/fandisk/fandisk_pmesh.c"
if ! cc -std=c99 -Wall -Werror -Iruntime/include -c "$pmc" -o "$tmp/layout.o" 2>"$tmp/layout.log"; then
    problems+="it does not compile: $(oneline <"$tmp/layout.log"); "
fi
want=$(sed -n 's/^#define MC_PMESH_LAYOUT \([0-9]*\).*/\1/p' runtime/include/modelc/pmesh.h)
grep -q "MC_PMESH_LAYOUT != $want\b" "$pmc" || problems+="it does not state layout $want (pmesh.h's); "
sed "s/MC_PMESH_LAYOUT != $want\b/MC_PMESH_LAYOUT != $((want + 1))/" "$pmc" >"$tmp/layout_other.c"
if cc -std=c99 -Iruntime/include -I"$out/fandisk" -c "$tmp/layout_other.c" -o "$tmp/layout_other.o" 2>"$tmp/layout_other.log"; then
    problems+="arrays of layout $((want + 1)) compiled against layout $want; "
else
    grep -q "error: #error.*MC_PMESH_LAYOUT" "$tmp/layout_other.log" ||
        problems+="another layout stopped the build without naming MC_PMESH_LAYOUT: $(oneline <"$tmp/layout_other.log"); "
fi
check_problems "fandisk: its pmesh.c states the arrays' layout (pmesh.h MC_PMESH_LAYOUT $want); another layout stops the build with that name" "$problems"

# ---- points-only bakes untouched -----------------------------------------------------------------
src=$(model_file fandisk)
"$modelc" "$src" -o "$tmp/a" --name fandisk --depth 5 -q && "$modelc" "$src" -o "$tmp/b" --name fandisk --depth 5 --as points -q
problems=$(diff -r "$tmp/a/fandisk" "$tmp/b/fandisk" >/dev/null 2>&1 || echo "--as points differs from no --as")
for f in fandisk_octree.c; do
    cmp -s "$tmp/a/fandisk/$f" "$out/fandisk/$f" || problems+=" $f differs between --as points and --as both"
done
grep -q "pmesh" "$tmp/a/fandisk/budget.json" && problems+=" a points-only budget.json mentions pmesh"
grep -q "&mc_octree_fandisk, 0, 0," "$tmp/a/fandisk/fandisk_model.c" || problems+=" a points-only model has a pmesh pointer"
check_problems "fandisk: --as points is the default; its octree descriptor is the same with --as both; no mesh in a points bake" "$problems"

exit $status
