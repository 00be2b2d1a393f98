#!/usr/bin/env bash
# Generator properties on real models: determinism, chunk limits and reassembly, budget.json,
# --help, progress output, and that the output compiles in any split.
set -u
cd "$(dirname "$0")/../.."
modelc=${1:-build/bin/modelc}
TAP_PREFIX="gen: "
. tests/lib.sh
temp_dir
nok() { notok "$1"; }
check() { check_cmd "$@"; }   # check NAME COMMAND...

src=build/models/nefertiti.off
pts=build/models/kitten.xyz

# determinism: same input and options, byte-identical output (twice in a row, and from another
# working directory through another path)
"$modelc" "$src" -o "$tmp/a" -q && "$modelc" "$src" -o "$tmp/b" -q
check "same input and options give byte-identical output" diff -r "$tmp/a/nefertiti" "$tmp/b/nefertiti"
(cd "$tmp" && "$OLDPWD/$modelc" "$OLDPWD/$src" -o c -q)
check "output does not depend on the working directory" diff -r "$tmp/a/nefertiti" "$tmp/c/nefertiti"
"$modelc" "$pts" -o "$tmp/a" -q && "$modelc" "$pts" -o "$tmp/b" -q
check "point sets bake deterministically too" diff -r "$tmp/a/kitten" "$tmp/b/kitten"

# a build of the dump checker against one bake
rt=$(rt_objs | tr '\n' ' ')
# shellcheck disable=SC2086
link() { gcc -std=c99 -O1 -Iruntime/include -o "$2" tests/gen/dump.c $rt "$1"/*.c; }

# chunking: small chunks and small files must change nothing but the split (at depth 7: 64-byte
# chunks of depth 8 make some 1,500 files, and compiling them was most of this suite's time). A
# file holds 4 chunks (--file-bytes), the 64-byte chunks' 32 (2048 bytes: 49 files, not 404, each a
# compiler run; the 1000-byte chunks check --file-bytes), with GEN_DEEP=1 (make stress) 4 too
for limit in 64 1000 65536; do
    fbytes=$((limit * 4))
    [ "$fbytes" -lt 2048 ] && [ "${GEN_DEEP:-0}" != 1 ] && fbytes=2048
    "$modelc" build/models/bunny00.off -o "$tmp/chunk$limit" --name bunny -q --depth 7 --chunk-bytes $limit --file-bytes $fbytes
    if link "$tmp/chunk$limit/bunny" "$tmp/dump$limit" && "$tmp/dump$limit" $limit >"$tmp/dump$limit.txt"; then
        ok "--chunk-bytes $limit: every chunk within the limit, counts add up, chunks end between the groups read at once"
    else
        nok "--chunk-bytes $limit: $(grep -v '^level [0-9]* nodes\|^frame' "$tmp/dump$limit.txt" | head -n 3 | tr '\n' ' ')"
    fi
    # the largest array in the .c files, counted from the initialisers themselves
    biggest=$(awk '/\] = \{/ {n=0; on=1; next} on && /^\};/ {if (n>max) max=n; on=0} on {n+=gsub(/,/,",")} END {print max+0}' "$tmp/chunk$limit/bunny"/bunny_data_*.c)
    check "--chunk-bytes $limit: largest emitted array has $biggest <= $limit bytes" test "$biggest" -le "$limit"
done
check "chunks reassemble to the same streams and the same frame (64 vs 65536)" diff "$tmp/dump64.txt" "$tmp/dump65536.txt"
check "chunks reassemble to the same streams and the same frame (1000 vs 65536)" diff "$tmp/dump1000.txt" "$tmp/dump65536.txt"
nfiles=$(ls "$tmp/chunk1000/bunny"/bunny_data_*.c | wc -l)
check "--file-bytes spreads the data over several files ($nfiles)" test "$nfiles" -gt 10

# budget.json agrees with the emitted arrays and the octree
check "budget.json: flash totals, points and bits per point agree with the arrays" python3 - "$tmp/chunk1000/bunny" <<'PY'
import json, re, sys, glob
d = sys.argv[1]
b = json.load(open(d + "/budget.json"))
sizes = {}
for f in glob.glob(d + "/bunny_data_*.c"):
    for sym, n in re.findall(r"const uint8_t (\w+)\[(\d+)\]", open(f).read()):
        sizes[sym] = int(n)
pal = b["flash"]["palette"]
assert sum(sizes.values()) + pal == b["flash"]["total"], "total"
assert {k: v for k, v in b["flash"]["arrays"].items() if not k.endswith("_palette")} == sizes, "arrays"
assert b["points"] == b["points_per_level"][-1], "points"
assert b["flash"]["masks"] == sum(b["points_per_level"][:-1]), "masks"
assert b["flash"]["colors"] == sum(b["points_per_level"][1:]), "colours"
assert abs(b["bits_per_point"]["geometry"] - 8 * b["flash"]["masks"] / b["points"]) < 1e-9
assert pal == 3 * b["palette_entries"] and 1 <= b["palette_entries"] <= 256
assert b["ram"]["total"] == 3 * b["screen"][0] * b["screen"][1]
PY

# the model descriptor: name, parts, and the normalization against the file's own bounding box
check "model descriptor: name bunny, up y, an octree, no pmesh or edges" grep -qx 'model bunny up y octree yes pmesh no edges no' "$tmp/dump65536.txt"
"$modelc" build/models/man.off -o "$tmp/up" -q --depth 5 --up z
# a tetrahedron off the origin with a different extent per axis: a centre or side taken in the
# generator's turned (y-up) frame instead of the file's would be caught
printf 'OFF\n4 4 0\n10 20 30\n11 20 30\n10 22 30\n10 20 33\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' >"$tmp/tet.off"
"$modelc" "$tmp/tet.off" -o "$tmp/up" -q --depth 4 --up z --name tet
check "model descriptor: centre and side (Q32.32) are the file's bounding cube, up axis recorded (bunny00 up y; man, a tetrahedron up z)" \
    python3 - "$tmp/chunk65536/bunny/bunny_model.c" build/models/bunny00.off y "$tmp/up/man/man_model.c" build/models/man.off z \
    "$tmp/up/tet/tet_model.c" "$tmp/tet.off" z <<'PY'
import re, sys
args = sys.argv[1:]
for model_c, off, up in zip(args[0::3], args[1::3], args[2::3]):
    text = open(model_c).read()
    q = [int(v) for v in re.findall(r"INT64_C\((-?\d+)\)", text)]
    assert len(q) == 4, q
    centre, side = [v / 2**32 for v in q[:3]], q[3] / 2**32
    words = open(off).read().split()
    nv = int(words[1])
    pts = [[float(w) for w in words[4 + 3 * i:7 + 3 * i]] for i in range(nv)]
    lo = [min(p[a] for p in pts) for a in range(3)]
    hi = [max(p[a] for p in pts) for a in range(3)]
    ext = max(h - l for l, h in zip(lo, hi))
    for a in range(3):   # in the file's own axes, whatever the up axis
        assert abs(centre[a] - (lo[a] + hi[a]) / 2) < 1e-6 * ext, (model_c, a, centre, lo, hi)
    assert abs(side - ext) < 1e-6 * ext, (model_c, side, ext)
    assert ("MC_UP_Z" if up == "z" else "MC_UP_Y") in text, (model_c, up)
PY

# palette: --palette 16 quantizes to at most 16 entries and still renders
"$modelc" build/models/b9_training.ply -o "$tmp/pal" -q --palette 16 --depth 6
check "--palette 16 gives at most 16 entries" python3 -c "import json,sys; sys.exit(json.load(open('$tmp/pal/b9_training/budget.json'))['palette_entries'] > 16)"

# --help names every option
help=$("$modelc" --help)
for opt in --out --name --depth --spacing --palette --chunk-bytes --file-bytes --screen --quiet --version; do
    check "--help covers $opt" grep -q -- "$opt" <<<"$help"
done

# progress: nothing on stderr when it is not a terminal; on a terminal, a step over a second shows
# (bunny00 at depth 9: about 8 s of CPU, most of it in sampling; depth 10 took 30 s for no more)
# (the bake without a terminal is fandisk's deeper bake below, without -q: steps of several seconds,
# nothing on stderr; it is the deeper bake the level check needs, so no bake is made for this alone)
script -qec "$modelc build/models/bunny00.off -o $tmp/p --depth 9" /dev/null >"$tmp/tty.txt" 2>&1
check "progress on a terminal for steps over a second" grep -q 'modelc: [a-z ]* *[0-9]*%\|modelc: [a-z ]* done' "$tmp/tty.txt"

# a deeper mesh bake drawn at a coarser level (the level of detail) draws what a bake of that depth
# draws: level l of a depth-D bake has the cells and colours of a depth-l bake, for l from 8
# (gen/voxel.hpp kSampledLevel) to D, and the levels above 8 those of the depth-8 bake. Read back
# from the generated arrays (tests/gen/levels.c: each node's Morton code and palette RGB, level by
# level), so palettes that number the same colours differently still compare equal (the models
# here are grey: every colour is exact in the palette). bunny00 at 9 is the bake of the progress
# check above. With GEN_DEEP=1 (make stress) fandisk is baked at 10 as well, which checks a level
# between 8 and the bake's depth too (its bake and reading take 30 s of CPU).
levels_of() {   # levels_of BAKE_DIR LAST OUT: build tests/gen/levels.c against the bake, print levels 1..LAST
    gcc -std=c99 -O0 -Iruntime/include -o "$3.bin" tests/gen/levels.c "$1"/*.c && "$3.bin" "$2" >"$3"
}
# the depth-8 bakes: the catalogue's own (make views made them with these options: --depth 8 and
# nothing else) when make says they are up to date with this generator, else baked here
for m in bunny00 fandisk; do
    if [ "$modelc" = build/bin/modelc ] && [ "$(mkvar "$m.opts") $(mkvar BAKE_OPTS)" = "--depth 8 " ] &&
        make -s -q "build/$m/budget.json" 2>/dev/null; then
        mkdir -p "$tmp/lv8" && ln -s "$PWD/build/$m" "$tmp/lv8/$m"
    else
        "$modelc" "build/models/$m.off" -o "$tmp/lv8" -q --depth 8
    fi
done
"$modelc" build/models/fandisk.off -o "$tmp/lv9" --depth 9 2>"$tmp/stderr.txt" >/dev/null
check "quiet when stderr is not a terminal (fandisk at depth 9, steps of seconds)" test ! -s "$tmp/stderr.txt"
pairs=("bunny00 8 $tmp/p" "fandisk 8 $tmp/lv9")
if [ "${GEN_DEEP:-0}" = 1 ]; then
    "$modelc" build/models/fandisk.off -o "$tmp/lv10" -q --depth 10
    pairs+=("fandisk 9 $tmp/lv10")
fi
for pair in "${pairs[@]}"; do
    read -r m l deep <<<"$pair"
    d=$(python3 -c "import json,sys; print(len(json.load(open(sys.argv[1]))['points_per_level']) - 1)" "$deep/$m/budget.json")
    if levels_of "$tmp/lv$l/$m" "$l" "$tmp/levels.$m.$l.txt" && levels_of "$deep/$m" "$l" "$tmp/levels.$m.$l.of$d.txt"; then
        if cmp -s "$tmp/levels.$m.$l.txt" "$tmp/levels.$m.$l.of$d.txt"; then
            ok "$m: levels 1..$l of the depth-$d bake are the depth-$l bake's, cell for cell and colour for colour ($(grep -c "^$l " "$tmp/levels.$m.$l.txt") cells at level $l)"
        else
            read -r more fewer recoloured < <(python3 - "$tmp/levels.$m.$l.txt" "$tmp/levels.$m.$l.of$d.txt" <<'PY'
import sys
a, b = ({tuple(x.split()[:2]): x.split()[2:] for x in open(f)} for f in sys.argv[1:3])
print(len(b.keys() - a.keys()), len(a.keys() - b.keys()), sum(a[k] != b[k] for k in a.keys() & b.keys()))
PY
            )
            nok "$m: levels 1..$l of the depth-$d bake are not the depth-$l bake's: $more nodes more, $fewer fewer, $recoloured of the common ones coloured differently"
        fi
    else
        nok "$m: cannot read the levels of the depth-$l and depth-$d bakes"
    fi
done

# normal cones (gen/cones.hpp): made for a closed, non-self-intersecting mesh, each holding the
# outward normal of every face its node's cube meets (tests/gen/cones_check.py, in double precision,
# independently of CGAL), counted in budget.json; none for an open mesh, a point set or --cull off
"$modelc" build/models/bunny00.off -o "$tmp/cones" --depth 6 -q
check "cones of bunny00 (closed) at depth 6 hold every face normal of their cubes; subtree counts right" \
    python3 tests/gen/cones_check.py build/models/bunny00.off "$tmp/cones/bunny00" bunny00
"$modelc" build/models/head.off -o "$tmp/cones" --depth 6 -q
"$modelc" build/models/kitten.xyz -o "$tmp/cones" --depth 6 -q
"$modelc" build/models/bunny00.off -o "$tmp/cones" --name nocull --depth 6 --cull off -q
check "budget.json: cones made for bunny00 (their bytes in flash, 7 a node of levels 1..D-3); not for head (open), kitten (points), --cull off" \
    python3 - "$tmp/cones" <<'PY'
import json, sys
b = {n: json.load(open("%s/%s/budget.json" % (sys.argv[1], n))) for n in ("bunny00", "head", "kitten", "nocull")}
assert b["bunny00"]["cones"] == {"made": True}, b["bunny00"]["cones"]
nodes = sum(b["bunny00"]["points_per_level"][1:6 - 2])
assert b["bunny00"]["flash"]["cones"] == 7 * nodes, (b["bunny00"]["flash"]["cones"], nodes)
for n, why in (("head", "not closed"), ("kitten", "point set"), ("nocull", "--cull off")):
    assert not b[n]["cones"]["made"] and why in b[n]["cones"]["why_not"], (n, b[n]["cones"])
    assert b[n]["flash"]["cones"] == 0, n
PY

# bad options: one line, exit 2, no output
"$modelc" build/models/nefertiti.off -o "$tmp/bad" --depth 13 2>"$tmp/e.txt"
st=$?
check "--depth 13 is refused with one line and status 2" test "$st" = 2 -a "$(wc -l <"$tmp/e.txt")" = 1 -a ! -e "$tmp/bad"
"$modelc" build/models/nefertiti.off -o "$tmp/bad" --name 'no good' 2>"$tmp/e.txt"
st=$?
check "a name that is not a C identifier is refused" test "$st" = 2 -a "$(wc -l <"$tmp/e.txt")" = 1 -a ! -e "$tmp/bad"
exit $((fails > 0))
