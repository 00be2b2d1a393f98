#!/usr/bin/env bash
# glTF input (gen/input/gltf.cpp). For bunny00 and fandisk (make models), tests/gen/make_gltf.py
# writes the mesh the OFF reader reads as glTF in several forms (data URI, GLB, external files, a
# node hierarchy whose matrix and TRS transforms undo the stored positions exactly, a mirroring
# node, instances) and with colour (a baseColorFactor, COLOR_0 as bytes and floats, textures as a
# data URI, a buffer view and a file, with wrap modes), each beside an OFF twin: the glTF file must
# read to the twin's model bit for bit (tests/gen/model_dump.cpp) and bake to the same files. Then
# Debian's glTF samples (assimp-testmodels), and malformed files: exit 1, one line "modelc: ...",
# no output.
#
# usage: tests/gen/gltf.sh [MODELC]        (default build/bin/modelc)
set -u
cd "$(dirname "$0")/../.."
MODELC=${1:-build/bin/modelc}
TAP_PREFIX="gltf: "
. tests/lib.sh
temp_dir
[ -x "$MODELC" ] || { notok "setup" "$MODELC is not an executable (make gen)"; exit 1; }

# the dump tool, linked with the generator's own reader objects (tests/lib.sh model_dump_tool)
if ! dump=$(model_dump_tool 2>"$tmp/cc.txt"); then
    notok "build the model dump tool" "$(oneline <"$tmp/cc.txt")"
    exit 1
fi

# twin_dump TWIN: what the dump tool prints for TWIN, read once (an OFF twin serves several checks)
mkdir -p "$tmp/twin-dumps"
twin_dump() {
    local f=$tmp/twin-dumps/${1//\//_}
    [ -f "$f" ] || "$dump" "$1" >"$f" 2>&1
    echo "$(<"$f")"
}
# same NAME FILE TWIN: FILE reads to exactly TWIN's model
same() {
    local a b
    a=$("$dump" "$2" 2>&1)
    b=$(twin_dump "$3")
    if [[ $b == modelc:* ]]; then notok "$1" "the twin does not read: $b"
    elif [ "$a" != "$b" ]; then notok "$1" "$(diff <(echo "$b") <(echo "$a") | head -n 6 | oneline)"
    else ok "$1"; fi
}

# bake FILE DIR [OPTIONS...]: DIR/m/, the bake of FILE named m; its source file's name replaced by SRC
bake() {
    local f=$1 dir=$2
    shift 2
    rm -rf "$dir"
    mkdir -p "$dir"
    "$MODELC" "$f" -o "$dir" --name m -q "$@" >"$dir.log" 2>&1 || return 1
    sed -i "s/$(basename "$f")/SRC/g" "$dir"/m/*
}

# same_bake NAME FILE TWIN [OPTIONS...]: the two bakes are the same files, byte for byte
# (a twin baked with the same options earlier in the suite is not baked again: the OFF's plain bake
# serves both the .glb's check and the hierarchy's)
same_bake() {
    local name=$1 a=$2 b=$3 twin
    shift 3
    if ! bake "$a" "$tmp/bake-a" "$@"; then notok "$name" "bake of $a failed: $(oneline <"$tmp/bake-a.log")"; return; fi
    twin=$tmp/twin-$(echo "$b $*" | md5sum | cut -c1-12)
    if [ ! -d "$twin/m" ]; then
        if ! bake "$b" "$twin" "$@"; then notok "$name" "bake of $b failed: $(oneline <"$twin.log")"; return; fi
    fi
    check_problems "$name" "$(diff -r "$tmp/bake-a/m" "$twin/m" | head -n 4 | oneline)"
}

# palette DIR: a bake's palette, one "r g b" line per entry
palette() {
    sed -n '/_palette\[[0-9]*\] = {/,/};/{/_palette/d;/};/d;p}' "$1"/m/m_octree.c | tr -cs '0-9' '\n' | grep . |
        paste -d ' ' - - -
}

# ------------------------------------------------------------------------------ catalogue meshes
for model in bunny00 fandisk; do
    off=$(model_file "$model") || { notok "$model: source file" "cannot extract it (make models)"; continue; }
    d=$tmp/$model
    mkdir -p "$d"
    "$dump" "$off" >"$d/orig.dump" || { notok "$model: read the OFF" "$(head -c 300 "$d/orig.dump")"; continue; }
    if ! python3 tests/gen/make_gltf.py "$d/orig.dump" "$d" 2>"$tmp/py.txt"; then
        notok "$model: tests/gen/make_gltf.py" "$(oneline <"$tmp/py.txt")"
        continue
    fi
    m="$model:"
    same "$m the OFF twins are exact (%.9g text)" "$d/original.off" "$off"
    same "$m .gltf, buffer as a data URI" "$d/plain.gltf" "$off"
    same "$m .glb, BIN chunk" "$d/plain.glb" "$off"
    same "$m .gltf with its .bin beside it" "$d/external.gltf" "$off"
    same "$m default scene 1: a matrix node over a TRS node, undone exactly" "$d/hierarchy.gltf" "$off"
    same "$m a mirroring node (scale -1): faces stored clockwise come back counter-clockwise" "$d/mirror.glb" "$off"
    same "$m one mesh under two nodes: both instances, the second translated" "$d/instances.gltf" "$d/instances.off"
    same "$m a white baseColorFactor is no colour: a colourless model" "$d/white.gltf" "$off"
    same "$m baseColorFactor (linear) as sRGB bytes on every vertex" "$d/factor.gltf" "$d/factor.off"
    same "$m COLOR_0, normalized bytes (linear) to sRGB" "$d/colour0.glb" "$d/colour0.off"
    same "$m COLOR_0, floats, times the baseColorFactor" "$d/colour0f.gltf" "$d/colour0f.off"
    same "$m texture as a data URI: REPEAT and MIRRORED_REPEAT, nearest texel" "$d/texture.gltf" "$d/texture.off"
    same "$m texture and buffer as files beside the .gltf" "$d/texture-file.gltf" "$d/texture.off"
    same "$m texture in a GLB buffer view, CLAMP_TO_EDGE, TEXCOORD_1 as normalized shorts, times a factor" \
        "$d/texture.glb" "$d/texture-glb.off"
    if [ "$model" = bunny00 ]; then
        same "TRIANGLE_STRIP in the spec's corner order; points and lines primitives skipped" "$d/strip.gltf" "$d/strip.off"
        same "TRIANGLE_FAN in the spec's corner order; points and lines primitives skipped" "$d/fan.gltf" "$d/fan.off"
    fi
    # the bakes: the same bytes as the OFF's (the transforms are undone exactly: no tolerance); at the
    # catalogue's depth for the plain .glb, at depth 6 for the rest (a bake is a function of the model
    # read, which the dumps above compare bit for bit: the shallower bake shows the same at a quarter
    # of the time)
    same_bake "$m bake of the .glb is the OFF's, byte for byte" "$d/plain.glb" "$off"
    same_bake "$m bake of the transformed hierarchy is the OFF's" "$d/hierarchy.gltf" "$off" --depth 6
    same_bake "$m bake of the mirrored .glb (--as both: orientation matters) is the OFF's" "$d/mirror.glb" "$off" --as both --depth 6
    same_bake "$m bake with COLOR_0 is its COFF twin's" "$d/colour0.glb" "$d/colour0.off" --depth 6
    same_bake "$m bake with a texture is its COFF twin's" "$d/texture.glb" "$d/texture-glb.off" --depth 6
    if bake "$d/factor.gltf" "$tmp/bake-f" --depth 6; then
        got=$(palette "$tmp/bake-f" | oneline)
        check_problems "$m a uniform baseColorFactor bakes a one-colour palette: $(cat "$d/factor.rgb") (linear 0.2 0.5 0.8)" \
            "$([ "$got" = "$(cat "$d/factor.rgb")" ] || echo "palette: $got")"
    else
        notok "$m bake of factor.gltf" "$(oneline <"$tmp/bake-f.log")"
    fi
    if bake "$d/texture.gltf" "$tmp/bake-t" --depth 6; then
        n=$(palette "$tmp/bake-t" | wc -l)
        check_problems "$m a textured bake has the texture's colours (palette of $n entries)" \
            "$([ "$n" -ge 16 ] || echo "only $n palette entries")"
    else
        notok "$m bake of texture.gltf" "$(oneline <"$tmp/bake-t.log")"
    fi
done

# ------------------------------------------------------------------------------ Debian's samples
S=/usr/share/assimp/models/glTF2
if [ ! -d "$S" ]; then
    skip "Debian's glTF samples" "package assimp-testmodels is not installed (make deps installs it)"
else
    B=$S/BoxTextured-glTF
    same "assimp BoxTextured: external .bin and .png read as the embedded .gltf" "$B/BoxTextured.gltf" \
        "$S/BoxTextured-glTF-Embedded/BoxTextured.gltf"
    same "assimp BoxTextured: .glb read as the .gltf" "$S/BoxTextured-glTF-Binary/BoxTextured.glb" "$B/BoxTextured.gltf"
    head=$("$dump" "$B/BoxTextured.gltf" | head -n 1)
    check_problems "assimp BoxTextured: 24 vertices, 12 triangles, coloured from its texture" \
        "$([ "$head" = "mesh points 24 triangles 12 colours 24 normals 0" ] || echo "$head")"
    if bake "$S/2CylinderEngine-glTF-Binary/2CylinderEngine.glb" "$tmp/bake-e" --depth 7; then
        n=$(palette "$tmp/bake-e" | wc -l)
        check_problems "assimp 2CylinderEngine.glb (1.8 MB, 34 materials) bakes, its materials' colours in the palette" \
            "$([ "$n" -ge 8 ] || echo "only $n palette entries")"
    else
        notok "assimp 2CylinderEngine.glb bakes" "$(oneline <"$tmp/bake-e.log")"
    fi
    # glTF-Asset-Generator's unit square in every primitive mode: the triangle modes give two
    # triangles facing +z (the spec's corner order) of area 1; points and lines are not read
    P=$S/glTF-Asset-Generator/Mesh_PrimitiveMode
    for k in 04 05 06 11 12 13 14 15; do
        why=$("$dump" "$P/Mesh_PrimitiveMode_$k.gltf" | python3 -c '
import sys
v, area, problems = [], 0.0, []
for line in sys.stdin:
    w = line.split()
    if w[0] == "v": v.append([float.fromhex(x) for x in w[1:4]])
    elif w[0] == "f":
        a, b, c = (v[int(i)] for i in w[1:4])
        z = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        if z <= 0: problems.append("triangle %s faces -z" % " ".join(w[1:4]))
        area += z / 2
    elif w[0] == "modelc:": problems.append(line.strip())
if abs(area - 1) > 1e-6: problems.append("area %g" % area)
print("; ".join(problems))')
        check_problems "assimp Mesh_PrimitiveMode_$k: two triangles facing +z, area 1" "$why"
    done
    for k in 00 01 02 03 07 08 09 10; do
        out=$("$MODELC" "$P/Mesh_PrimitiveMode_$k.gltf" -o "$tmp/pm" --name m -q 2>&1)
        check_problems "assimp Mesh_PrimitiveMode_$k (points or lines): refused, nothing to draw" \
            "$([[ $out == "modelc: "*"no triangle primitives to draw (1 points or lines primitives are not read)" ]] || echo "$out")"
    done
    for f in BoxBadNormals-glTF-Binary/BoxBadNormals.glb BoxTexcoords-glTF/boxTexcoords.gltf \
        BoxTextured-glTF-pbrSpecularGlossiness/BoxTextured.gltf ClearCoat-glTF/ClearCoatTest.gltf cameras/Cameras.gltf \
        glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf issue_3269/texcoord_crash.gltf \
        simple_skin/simple_skin.gltf textureTransform/TextureTransformTest.gltf; do
        if bake "$S/$f" "$tmp/bake-s" --depth 5; then ok "assimp $f bakes"; else notok "assimp $f bakes" "$(oneline <"$tmp/bake-s.log")"; fi
    done
fi

# ------------------------------------------------------------------------------ malformed files
# expect NAME FILE PLACE REGEX: exit 1, one stderr line "modelc: FILE:PLACE: MESSAGE" (PLACE "-":
# none) with MESSAGE matching REGEX, and nothing in the output directory
expect() {
    local name=$1 file=$2 place=$3 regex=$4 out=$tmp/out/$1 rc=0 why="" line prefix
    mkdir -p "$out"
    timeout 60 "$MODELC" "$file" -o "$out" --name model -q >/dev/null 2>"$tmp/stderr" || rc=$?
    line=$(cat "$tmp/stderr")
    if [ "$place" = - ]; then prefix="modelc: $file: "; else prefix="modelc: $file:$place: "; fi
    if [ "$rc" -ne 1 ]; then why="exit status $rc, expected 1: $(oneline <"$tmp/stderr")"
    elif [ "$(awk 'END { print NR }' "$tmp/stderr")" -ne 1 ]; then why="stderr is not one line: $(oneline <"$tmp/stderr")"
    elif [ "${line#"$prefix"}" = "$line" ]; then why="'$line' does not start with '$prefix'"
    elif ! [[ ${line#"$prefix"} =~ $regex ]]; then why="'${line#"$prefix"}' does not match /$regex/"
    elif [ -n "$(ls -A "$out")" ]; then why="output left: $(ls -A "$out" | oneline)"; fi
    check_problems "malformed: $name: $(echo "${line#"$prefix"}" | cut -c1-110)" "$why"
}
b=$tmp/bunny00/bad
if [ -d "$b" ]; then
    jl=$(od -An -tu4 -j12 -N4 "$b/binpast.glb" | tr -d ' ')
    expect truncated.glb "$b/truncated.glb" "byte 8" "the header says [0-9]+ bytes but the file has [0-9]+ \(truncated\?\)"
    expect badjson.gltf "$b/badjson.gltf" 3 "^JSON: syntax error"
    expect index-range.gltf "$b/index-range.gltf" - "indices: index 8 \(element 5\) is out of range \(POSITION has 8 vertices\)"
    expect beyond.gltf "$b/beyond.gltf" - "POSITION \(accessors\[0\]\): 9 elements .* run past the end of bufferViews\[0\]"
    expect noposition.gltf "$b/noposition.gltf" - "attributes: no POSITION"
    expect extreq.gltf "$b/extreq.gltf" - "extensionsRequired: extension 'KHR_draco_mesh_compression' is not supported"
    expect nonfinite.glb "$b/nonfinite.glb" - "POSITION: vertex 7 has a coordinate that is not finite"
    expect cycle.gltf "$b/cycle.gltf" - "nodes\[0\] is a child of nodes\[1\]"
    expect dag.gltf "$b/dag.gltf" - "nodes\[0\] is already a child of nodes\[1\]"
    expect missing-bin.gltf "$b/missing-bin.gltf" - "^tinygltf: File not found : missing-bin.bin"
    expect postype.gltf "$b/postype.gltf" - "VEC3 of unsigned short is not one of the types allowed here"
    expect sparse.gltf "$b/sparse.gltf" - "sparse accessors are not supported"
    expect notimage.gltf "$b/notimage.gltf" - "images\[0\]: neither PNG nor JPEG"
    expect hugepng.gltf "$b/hugepng.gltf" - "images\[0\]: 9000 x 9000 texels \(at most 67108864\)"
    expect lyingpng.gltf "$b/lyingpng.gltf" - "images\[0\]: 4000 x 4000 texels cannot be coded in [0-9]+ bytes"
    expect version1.gltf "$b/version1.gltf" - "glTF '1.0' is not supported"
    expect deep.gltf "$b/deep.gltf" - "nested deeper than 64 levels"
    expect neg-index.gltf "$b/neg-index.gltf" - "material: -1 is out of range"
    expect int-range.gltf "$b/int-range.gltf" - "indices: 4294967296 is out of range"
    expect mode.gltf "$b/mode.gltf" - "mode: 9 is not a primitive mode"
    expect huge-number.gltf "$b/huge-number.gltf" 1 "JSON: number overflow parsing '1e999'"
    expect badmagic.glb "$b/badmagic.glb" "byte 0" "no 'glTF' magic"
    expect "binpast.glb (tinygltf 2.7 would read 8 bytes past the file)" "$b/binpast.glb" "byte $((20 + jl))" \
        "the chunk's [0-9]+ bytes run past the end of the file"
    expect "imageview.glb (tinygltf 2.7's image loader would let stb_image read past the buffer)" "$b/imageview.glb" - \
        "images\[0\]: bufferViews\[[0-9]+\] runs past the end of buffers\[0\]"
    expect emptybuffer.glb "$b/emptybuffer.glb" - "buffers\[0\].byteLength: 0 bytes"
    expect json-named-glb.glb "$b/json-named-glb.glb" "byte 0" "this is a JSON glTF"
    expect glb-named-gltf.gltf "$b/glb-named-gltf.gltf" "byte 0" "this is a binary glTF"
    expect no-asset.gltf "$b/no-asset.gltf" - "asset.version is missing"
    if [ -d "$S" ]; then
        expect "assimp IndexOutOfRange" "$S/IndexOutOfRange/IndexOutOfRange.gltf" - "index 255 \(element 0\) is out of range"
        expect "assimp MissingBin" "$S/MissingBin/BoxTextured.gltf" - "File not found : BoxTextured0.bin"
        expect "assimp RecursiveNodes" "$S/RecursiveNodes/RecursiveNodes.gltf" - "a scene lists root nodes"
        expect "assimp draco" "$S/draco/2CylinderEngine.gltf" - "KHR_draco_mesh_compression' is not supported"
        expect "assimp BoxWithInfinites" "$S/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb" - "not finite"
    fi
    # a few hundred bytes that claim four billion vertices, in a small address space
    rc=0
    (ulimit -v 400000 && exec "$MODELC" "$b/absurd-count.gltf" -o "$tmp/out" --name absurd -q) 2>"$tmp/err.txt" >/dev/null || rc=$?
    check_problems "absurd-count.gltf ($(wc -c <"$b/absurd-count.gltf") bytes, 4e9 vertices) under ulimit -v 400000: one error line" \
        "$([ "$rc" = 1 ] && [ "$(wc -l <"$tmp/err.txt")" = 1 ] && grep -q 'run past the end' "$tmp/err.txt" ||
            echo "exit $rc: $(oneline <"$tmp/err.txt")")"
else
    notok "malformed files" "not written (bunny00 missing?)"
fi
exit $status
