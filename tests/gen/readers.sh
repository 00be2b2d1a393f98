#!/usr/bin/env bash
# The readers (gen/input/) on valid files that exporters really write but that a naive reader
# trips over: comments, CRLF line ends, odd headers, extra properties, unusual keyword spelling.
# Each such file must give exactly the model of an equivalent plain file (tests/gen/model_dump.cpp
# prints both, bit for bit), or the model stated here. Then absurd headers: a file of a few bytes
# that declares millions of elements must fail with one error line inside a small address space.
#
# usage: tests/gen/readers.sh [MODELC]        (default build/bin/modelc)
set -u
cd "$(dirname "$0")/../.."
modelc=${1:-build/bin/modelc}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/modelc-readers.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT
TAP_PREFIX="readers: "
. tests/lib.sh

# the dump tool, linked with the generator's own reader objects (tests/lib.sh model_dump_tool)
if ! dump=$(model_dump_tool 2>"$tmp/cc.txt"); then
    notok "build the model dump tool" "$(oneline <"$tmp/cc.txt")"
    exit 1
fi

# same NAME FILE PLAIN: FILE gives the same model as PLAIN, and PLAIN reads at all.
same() {
    local a b
    a=$("$dump" "$2" 2>&1)
    b=$("$dump" "$3" 2>&1)
    if [[ $b == modelc:* ]]; then notok "$1" "the plain file does not read: $b"
    elif [ "$a" != "$b" ]; then notok "$1" "$(diff <(echo "$b") <(echo "$a") | head -n 6 | oneline)"
    else ok "$1"; fi
}
# gives NAME FILE EXPECTED: FILE gives exactly the model dump EXPECTED.
gives() {
    local a
    a=$("$dump" "$2" 2>&1)
    if [ "$a" = "$3" ]; then ok "$1"; else notok "$1" "$(diff <(echo "$3") <(echo "$a") | head -n 6 | oneline)"; fi
}
# one line of text per argument
lines() { printf '%s\n' "$@"; }
crlf() { sed 's/$/\r/'; }

d=$tmp/in
mkdir -p "$d"

# ---------------------------------------------------------------------------------- OFF
lines OFF '4 4 0' '0 0 0' '1 0 0' '0 1 0' '0 0 1' '3 0 2 1' '3 0 1 3' '3 0 3 2' '3 1 2 3' >"$d/plain.off"
lines '# exported by hand' '' OFF '# counts' '4 4 0' '0 0 0  # origin' '1 0 0' '' '0 1 0' '0 0 1#tip' \
    '3 0 2 1' '3 0 1 3 # side' '3 0 3 2' '3 1 2 3' '# end' >"$d/comments.off"
same "OFF: comments, blank lines, a comment before the header" "$d/comments.off" "$d/plain.off"
crlf <"$d/plain.off" >"$d/crlf.off"
same "OFF: CRLF line ends" "$d/crlf.off" "$d/plain.off"
lines '  OFF 4 4 0' '0 0 0' '1 0 0' '0 1 0' '0 0 1' '3 0 2 1' '3 0 1 3' '3 0 3 2' '3 1 2 3' >"$d/header.off"
same "OFF: counts on the header line, header indented" "$d/header.off" "$d/plain.off"
lines OFF '4 4 6' '0	0	0' '+1 0 0' '0 1.0 0' '0 0 1e0' '3 0 2 1' '3 0 1 3' '3 0 3 2' '3 1 2 3' >"$d/spelling.off"
same "OFF: tabs, '+1', '1.0', '1e0', an edge count" "$d/spelling.off" "$d/plain.off"
lines OFF '4 4 0' '0 0 0' '1 0 0' '0 1 0' '0 0 1' '3 0 2 1 255 0 0' '3 0 1 3 0.5 0.5 0.5 1' '3 0 3 2' '3 1 2 3' >"$d/facecolour.off"
same "OFF: face colours in a plain OFF are read past" "$d/facecolour.off" "$d/plain.off"
lines COFF '4 4 0' '0 0 0 255 0 0' '1 0 0 0 128 0 255' '0 1 0 0 0 255' '0 0 1 10 20 30' '3 0 2 1' '3 0 1 3' '3 0 3 2' '3 1 2 3' >"$d/colour.off"
lines COFF '4 4 0' '0 0 0 1. 0 0' '1 0 0 0 0.5 0 1' '0 1 0 0 0 1.0' '0 0 1 .1 0.2 0.3' '3 0 2 1' '3 0 1 3' '3 0 3 2' '3 1 2 3' >"$d/colourf.off"
gives "OFF: integer colours (RGB and RGBA)" "$d/colour.off" "$(lines 'mesh points 4 triangles 4 colours 4 normals 0' \
    'v 0x0p+0 0x0p+0 0x0p+0 rgb 255 0 0' 'v 0x1p+0 0x0p+0 0x0p+0 rgb 0 128 0' 'v 0x0p+0 0x1p+0 0x0p+0 rgb 0 0 255' \
    'v 0x0p+0 0x0p+0 0x1p+0 rgb 10 20 30' 'f 0 2 1' 'f 0 1 3' 'f 0 3 2' 'f 1 2 3')"
gives "OFF: decimal colours: a vertex is decimal when any of its values has a '.' (rounded, 0.5 -> 128)" "$d/colourf.off" "$(lines 'mesh points 4 triangles 4 colours 4 normals 0' \
    'v 0x0p+0 0x0p+0 0x0p+0 rgb 255 0 0' 'v 0x1p+0 0x0p+0 0x0p+0 rgb 0 128 0' 'v 0x0p+0 0x1p+0 0x0p+0 rgb 0 0 255' \
    'v 0x0p+0 0x0p+0 0x1p+0 rgb 26 51 77' 'f 0 2 1' 'f 0 1 3' 'f 0 3 2' 'f 1 2 3')"
lines STCNOFF '4 4 0' '0 0 0 0 0 1 255 0 0 0.5 0.5' '1 0 0 0 0 1 0 128 0 255 0 1' '0 1 0 0 0 1 0 0 255 1 1' '0 0 1 0 0 1 10 20 30 0 0' \
    '3 0 2 1' '3 0 1 3' '3 0 3 2' '3 1 2 3' >"$d/stcn.off"
same "STCNOFF: normals, colours then texture coordinates, as the format orders them" "$d/stcn.off" "$d/colour.off"
lines OFF '5 3 0' '0 0 0' '1 0 0' '1 1 0' '0 1 0' '0 0 1' '4 0 1 2 3' '3 0 0 4' '5 4 0 1 2 0' >"$d/polygons.off"
gives "OFF: a quad is fanned from its first corner; faces naming a vertex twice are dropped" "$d/polygons.off" "$(lines 'mesh points 5 triangles 2 colours 0 normals 0' \
    'v 0x0p+0 0x0p+0 0x0p+0' 'v 0x1p+0 0x0p+0 0x0p+0' 'v 0x1p+0 0x1p+0 0x0p+0' 'v 0x0p+0 0x1p+0 0x0p+0' 'v 0x0p+0 0x0p+0 0x1p+0' \
    'f 0 1 2' 'f 0 2 3')"
lines OFF '3 1 0' '0.1 0 0' '0 0.1 0' '0 0 1' '3 0 1 2' >"$d/float.off"
gives "OFF: mesh coordinates are the float the text rounds to" "$d/float.off" "$(lines 'mesh points 3 triangles 1 colours 0 normals 0' \
    'v 0x1.99999ap-4 0x0p+0 0x0p+0' 'v 0x0p+0 0x1.99999ap-4 0x0p+0' 'v 0x0p+0 0x0p+0 0x1p+0' 'f 0 1 2')"
# three triangles around one edge (a complex edge) keep their own vertices
lines OFF '5 3 0' '0 0 0' '1 0 0' '0 1 0' '0 -1 0' '0 0 1' '3 0 1 2' '3 1 0 3' '3 0 1 4' >"$d/complex.off"
gives "OFF: three faces sharing one edge keep the file's vertices" "$d/complex.off" "$(lines 'mesh points 5 triangles 3 colours 0 normals 0' \
    'v 0x0p+0 0x0p+0 0x0p+0' 'v 0x1p+0 0x0p+0 0x0p+0' 'v 0x0p+0 0x1p+0 0x0p+0' 'v 0x0p+0 -0x1p+0 0x0p+0' 'v 0x0p+0 0x0p+0 0x1p+0' \
    'f 0 1 2' 'f 1 0 3' 'f 0 1 4')"

# ---------------------------------------------------------------------------------- OBJ
lines 'v 0 0 0' 'v 1 0 0' 'v 0 1 0' 'v 0 0 1' 'f 1 3 2' 'f 1 2 4' 'f 1 4 3' 'f 2 3 4' >"$d/plain.obj"
lines '# header' 'mtllib ../../../../../../../../../../dev/zero' 'o thing' 'g group' 'v 0 0 0' 'vt 0 0' 'vn 0 0 1' \
    'v 1 0 0 1.0' 'v 0 1 0' 'usemtl red' 's off' 'f 1/1/1 3/1/1 2/1/1' 'v 0 0 1 # last' 'f 1//1 2//1 -1//1' 'f 1/1 4/1 3/1' \
    'l 1 2' 'f -3 -2 -1' >"$d/statements.obj"
same "OBJ: other statements skipped (mtllib naming a device is never opened), v/t/n corners, w, negative indices" "$d/statements.obj" "$d/plain.obj"
crlf <"$d/plain.obj" >"$d/crlf.obj"
same "OBJ: CRLF line ends" "$d/crlf.obj" "$d/plain.obj"
lines 'f 1 3 2' 'f 1 2 4' 'v 0 0 0' 'v 1 0 0' 'v 0 1 0' 'v 0 0 1' 'f 1 4 3' 'f 2 3 4' >"$d/forward.obj"
same "OBJ: faces before the vertices they name" "$d/forward.obj" "$d/plain.obj"
lines 'v 0 0 0' 'v 1 0 0' 'v 0 1 0' 'v 0 0 1' 'f 1 3 3 2' 'f 1 2 4 1' 'f 1 4 1 3 4' 'f 2 3 4' >"$d/repeats.obj"
same "OBJ: a face naming a vertex again keeps its first mention" "$d/repeats.obj" "$d/plain.obj"
lines 'v 0 0 0 1 0 0' 'v 1 0 0 0 0.5 0' 'v 0 1 0 0 0 1' 'v 0 0 1 0.1 0.2 0.3' 'f 1 3 2' >"$d/colour.obj"
gives "OBJ: vertex colours 0..1 to bytes (rounded)" "$d/colour.obj" "$(lines 'mesh points 4 triangles 1 colours 4 normals 0' \
    'v 0x0p+0 0x0p+0 0x0p+0 rgb 255 0 0' 'v 0x1p+0 0x0p+0 0x0p+0 rgb 0 128 0' 'v 0x0p+0 0x1p+0 0x0p+0 rgb 0 0 255' \
    'v 0x0p+0 0x0p+0 0x1p+0 rgb 26 51 77' 'f 0 2 1')"

# ---------------------------------------------------------------------------------- PLY
ply_plain() {  # FORMAT
    lines ply "format $1 1.0" 'element vertex 4' 'property float x' 'property float y' 'property float z' \
        'element face 4' 'property list uchar int vertex_indices' end_header
}
TETRA_LE='pack("f<12", 0,0,0, 1,0,0, 0,1,0, 0,0,1), pack("(C l<3)4", 3,0,2,1, 3,0,1,3, 3,0,3,2, 3,1,2,3)'
{ ply_plain ascii; lines '0 0 0' '1 0 0' '0 1 0' '0 0 1' '3 0 2 1' '3 0 1 3' '3 0 3 2' '3 1 2 3'; } >"$d/plain.ply"
{ ply_plain binary_little_endian; perl -e "print $TETRA_LE"; } >"$d/plain-le.ply"
same "PLY: binary little endian gives the ascii model" "$d/plain-le.ply" "$d/plain.ply"
{ lines ply 'format binary_big_endian 1.0' 'element vertex 4' 'property double x' 'property double y' 'property double z' \
    'element face 4' 'property list int uint vertex_indices' end_header
  perl -e 'print pack("d>12", 0,0,0, 1,0,0, 0,1,0, 0,0,1), pack("(l> L>3)4", 3,0,2,1, 3,0,1,3, 3,0,3,2, 3,1,2,3)'; } >"$d/be.ply"
same "PLY: big endian, double coordinates, int list counts" "$d/be.ply" "$d/plain.ply"
{ lines ply 'format binary_little_endian 1.0' 'comment made by a scanner' 'obj_info scale 1' 'element vertex 4' \
    'property float x' 'property float u' 'property float y' 'property float z' 'property uchar alpha' \
    'property list uchar float weights' 'element face 4' 'property ushort flags' 'property list ushort int vertex_indices' \
    'property list uchar float texcoord' 'element edge 1' 'property int vertex1' 'property int vertex2' 'comment last' end_header
  perl -e 'print pack("(f< f< f< f< C C f<)4", 0,9,0,0,255,1,7, 1,9,0,0,255,1,7, 0,9,1,0,255,1,7, 0,9,0,1,255,1,7)' \
    -e '; print pack("(S< S< l<3 C f<2)4", 1,3,0,2,1,2,.5,.5, 1,3,0,1,3,2,.5,.5, 1,3,0,3,2,2,.5,.5, 1,3,1,2,3,2,.5,.5), pack("l<2", 0, 1)'; } >"$d/extra.ply"
same "PLY: comments, obj_info, extra properties and lists, a third element" "$d/extra.ply" "$d/plain.ply"
{ lines ply 'format ascii 1.0' 'element material 1' 'property uchar ambient_red' 'property list uint8 float coefficients' \
    'element vertex 4' 'property float32 x' 'property float32 y' 'property float32 z' 'property uchar diffuse_red' \
    'property uchar diffuse_green' 'property uchar diffuse_blue' 'property float s' 'property float t' \
    'element face 4' 'property list uint8 int32 vertex_index' end_header '7 2 0.5 0.25' \
    '0 0 0 1 2 3 0 0' '1 0 0 1 2 3 1 0' '0 1 0 1 2 3 0 1' '0 0 1 1 2 3 1 1' '3 0 2 1' '3 0 1 3' '3 0 3 2' '3 1 2 3'; } >"$d/material.ply"
same "PLY: an element before the vertices, diffuse colours and s t read past, type aliases, vertex_index" "$d/material.ply" "$d/plain.ply"
{ ply_plain binary_little_endian | sed 's/$/\r/; s/^property float/property  float/'; perl -e "print $TETRA_LE"; } >"$d/crlf-bin.ply"
same "PLY: binary data after a CRLF header with doubled spaces" "$d/crlf-bin.ply" "$d/plain.ply"
{ ply_plain ascii | crlf; lines '0 0 0' '1 0 0' '' '0 1 0' '0 0 1' '3 0 2 1' '3 0 1 3' '3 0 3 2' '3 1 2 3' | crlf; } >"$d/crlf.ply"
same "PLY: ascii with CRLF line ends and a blank line" "$d/crlf.ply" "$d/plain.ply"
{ lines ply 'format ascii 1.0' 'element vertex 3' 'property float x' 'property float y' 'property float z' \
    'property float red' 'property float green' 'property float blue' 'element face 1' 'property list uchar int vertex_indices' end_header \
    '0 0 0 1 0 0' '1 0 0 0 0.5 0' '0 1 0 0.1 0.2 0.999' '3 0 1 2'; } >"$d/colourf.ply"
gives "PLY mesh: float colours to bytes (truncated, as before)" "$d/colourf.ply" "$(lines 'mesh points 3 triangles 1 colours 3 normals 0' \
    'v 0x0p+0 0x0p+0 0x0p+0 rgb 255 0 0' 'v 0x1p+0 0x0p+0 0x0p+0 rgb 0 127 0' 'v 0x0p+0 0x1p+0 0x0p+0 rgb 25 51 254' 'f 0 1 2')"
{ lines ply 'format ascii 1.0' 'element vertex 3' 'property double x' 'property double y' 'property double z' \
    'property float nx' 'property float ny' 'property float nz' 'property uchar red' 'property uchar green' 'property uchar blue' \
    'element face 0' 'property list uchar int vertex_indices' end_header '0.1 0 0 0 0 1 1 2 3' '1 0 0 0 1 0 4 5 6' '0 1 0 1 0 0 7 8 9'; } >"$d/points.ply"
gives "PLY point set: double coordinates kept as double, normals, colours; an empty face element" "$d/points.ply" \
    "$(lines 'point set points 3 triangles 0 colours 3 normals 3' 'v 0x1.999999999999ap-4 0x0p+0 0x0p+0 rgb 1 2 3 n 0x0p+0 0x0p+0 0x1p+0' \
        'v 0x1p+0 0x0p+0 0x0p+0 rgb 4 5 6 n 0x0p+0 0x1p+0 0x0p+0' 'v 0x0p+0 0x1p+0 0x0p+0 rgb 7 8 9 n 0x1p+0 0x0p+0 0x0p+0')"

# ---------------------------------------------------------------------------------- STL
facet() { lines '  facet normal 0 0 1' '    outer loop' "      vertex $1" "      vertex $2" "      vertex $3" '    endloop' '  endfacet'; }
{ echo 'solid t'; facet '0 0 0' '0 1 0' '1 0 0'; facet '0 0 0' '1 0 0' '0 0 1'; facet '0 0 0' '0 0 1' '0 1 0'; facet '1 0 0' '0 1 0' '0 0 1'; echo 'endsolid t'; } >"$d/plain.stl"
gives "STL: equal corners become one vertex, in order of first use" "$d/plain.stl" "$(lines 'mesh points 4 triangles 4 colours 0 normals 0' \
    'v 0x0p+0 0x0p+0 0x0p+0' 'v 0x0p+0 0x1p+0 0x0p+0' 'v 0x1p+0 0x0p+0 0x0p+0' 'v 0x0p+0 0x0p+0 0x1p+0' 'f 0 1 2' 'f 0 2 3' 'f 0 3 1' 'f 2 1 3')"
{ echo 'SOLID outer_shell'; facet '0 0 0' '0 1 0' '1 0 0' | sed 's/outer loop/OUTER LOOP/; s/vertex/VERTEX/'
  facet '0 0 0' '1 0 0' '0 0 1' | sed 's/outer loop/Outer  Loop/' | sed '3i\\'
  echo 'endsolid outer_shell'; echo 'solid second'; facet '-0 0 0' '0 0 1' '0 1 0'; facet '1 0 0' '0 1 0' '0 0 1' | crlf; echo 'endsolid'; } >"$d/odd.stl"
same "STL: keyword case, a solid named outer..., blank line in a facet, two solids, CRLF, -0" "$d/odd.stl" "$d/plain.stl"
perl -e 'print pack("a80 V", "solid but binary", 5); print pack("f<12 v", 0,0,1, @$_, 0) for [0,0,0, 0,1,0, 1,0,0], [0,0,0, 1,0,0, 0,0,1], [0,0,0, 0,0,1, 0,1,0], [1,0,0, 1,0,0, 0,0,1], [1,0,0, 0,1,0, 0,0,1]' >"$d/binary.stl"
same "binary STL whose header says 'solid'; a triangle with two equal corners dropped" "$d/binary.stl" "$d/plain.stl"

# ---------------------------------------------------------------------------------- XYZ
lines '0 0 0' '1 0 0' '0 1 0' '0 0 1' >"$d/plain.xyz"
printf '4\r\n# points\r\n0 0 0\r\n\r\n\t# tab then comment\r\n1 0 0 # x\r\n  \r\n0\t1\t0\r\n+0 0 1e0\r\n' >"$d/odd.xyz"
same "XYZ: count line, CRLF, blank lines holding only CR or spaces, tab before '#'" "$d/odd.xyz" "$d/plain.xyz"
lines '0.1 0 0 0 0 1' '1 0 0 0 1 0' >"$d/normals.xyz"
gives "XYZ: coordinates and normals as double" "$d/normals.xyz" "$(lines 'point set points 2 triangles 0 colours 0 normals 2' \
    'v 0x1.999999999999ap-4 0x0p+0 0x0p+0 n 0x0p+0 0x0p+0 0x1p+0' 'v 0x1p+0 0x0p+0 0x0p+0 n 0x0p+0 0x1p+0 0x0p+0')"

# ---------------------------------------------------------------------------------- CAO
# ViSP's cube (mbt/cube.cao in ViSP's images): faces from points only
cao_points() { lines 8 '0 0 0' '-0.084 0 0' '-0.084 0.084 0' '0 0.084 0' '0 0 0.084' '-0.084 0 0.084' '-0.084 0.084 0.084' '0 0.084 0.084'; }
{ lines V1; cao_points; lines 0 0 6 '4 0 4 5 1' '4 1 5 6 2' '4 6 7 3 2' '4 3 7 4 0' '4 0 1 2 3' '4 7 6 5 4' 0 0; } >"$d/plain.cao"
lines '# cube, 84 mm' '' V1 '# 3D points' '8                    # Number of points' ' 0.000  0.000  0.000 # Point with index 0' \
    '-0.084  0.000  0.000' '-0.0840 0.084  +0' '0	0.084	0' '0 0 84e-3' '' '-0.084 0 0.084' '-0.084 0.084 0.084' \
    '0.000 0.084 0.084 # point with index 7' '# 3D lines' '0                    # No 3D lines' '# 3D faces from lines' 0 \
    '# 3D faces from points' '6' '4 0 4 5 1 name=front useLod=true' '4 1 5 6 2   name="left side" minPolygonAreaThreshold=2500' \
    '4 6 7 3 2	name="back" # comment' '4 3 7 4 0 name=""' '4 0 1 2 3 name="a  b" useLod=false' '4 7 6 5 4#top' \
    '# 3D cylinders' 0 '# 3D circles' '0 # none' >"$d/comments.cao"
same "CAO: comments (before the header too), blank lines, tabs, '+0', '84e-3', attributes (quoted, with spaces, empty)" "$d/comments.cao" "$d/plain.cao"
crlf <"$d/comments.cao" >"$d/crlf.cao"
same "CAO: CRLF line ends" "$d/crlf.cao" "$d/plain.cao"
# the cube's 12 edges as 3D lines (some written backwards), five faces from them (lines in any
# order; the loop runs from the first line's first point) and the sixth from points
{ lines V1; cao_points; lines 12 '0 4 name=e0' '5 4 useLod=false' '1 5 minLineLengthThreshold=50' '0 1' '5 6' '2 6' '1 2' '6 7' \
    '3 7' '2 3' '4 7 name="last but one"' '0 3' 5 '4 0 2 3 1' '4 2 4 5 6' '4 7 8 9 5 name=back' '4 8 10 0 11' '4 3 6 9 11' \
    1 '4 7 6 5 4' 0 0; } >"$d/lines.cao"
same "CAO: faces from lines (lines backwards, out of order) give the faces from points" "$d/lines.cao" "$d/plain.cao"
{ lines V2 8 '0 0 0 10 20' '-0.084 0 0 1 2' '-0.084 0.084 0 1 2' '0 0.084 0 1 2' '0 0 0.084 1 2' '-0.084 0 0.084 1 2' \
    '-0.084 0.084 0.084 1 2' '0 0.084 0.084 -1 +2' 0 0 6 '4 0 4 5 1' '4 1 5 6 2' '4 6 7 3 2' '4 3 7 4 0' '4 0 1 2 3' '4 7 6 5 4'; } >"$d/v2.cao"
same "CAO: V2 (image coordinates after each point), no cylinder or circle counts (older files)" "$d/v2.cao" "$d/plain.cao"
lines V1 4 '0 0 0' '1 0 0' '0 1 0' '0 0 1' 2 '3 0' '1 0' 0 3 '3 0 2 1' '4 0 1 1 3' '3 1 2 3' 0 0 >"$d/edges.cao"
gives "CAO: 3D lines first, then each polygon's sides, every edge once, smaller index first; a face naming a point twice adds neither" \
    "$d/edges.cao" "$(lines 'mesh points 4 triangles 2 colours 0 normals 0 lines 6' 'v 0x0p+0 0x0p+0 0x0p+0' 'v 0x1p+0 0x0p+0 0x0p+0' \
        'v 0x0p+0 0x1p+0 0x0p+0' 'v 0x0p+0 0x0p+0 0x1p+0' 'f 0 2 1' 'f 1 2 3' 'l 0 3' 'l 0 1' 'l 0 2' 'l 1 2' 'l 2 3' 'l 1 3')"

# ---------------------------------------------------------------------------------- faces without area
# Vertices 2 and 4 share a position, so several faces have no area; some samples lie nearest to
# one of them, where CGAL's barycentric coordinates used to fail an assertion mid-bake.
lines OFF '5 12 0' '-0.000105088999 -0.000569254975 2' '-0.961000025 0 -0.0879999995' '2 0.823000014 4.07189608' '3 0 -4' \
    '2 0.823000014 4.07189608' '3 0 1 2' '3 3 0 2' '3 2 1 4' '3 1 2 4' '3 1 4 0' '3 2 4 1' '3 2 0 1' '3 3 0 2' \
    '3 2 1 4' '3 1 2 4' '3 1 4 0' '3 2 4 1' >"$d/no-area.off"
rc=0
"$modelc" "$d/no-area.off" -o "$tmp/out" --name noarea --depth 3 -q 2>"$tmp/err.txt" || rc=$?
check_problems "a mesh with faces of no area nearest to some samples bakes" \
    "$( [ "$rc" = 0 ] && [ -s "$tmp/out/noarea/budget.json" ] || echo "exit $rc: $(head -c 200 "$tmp/err.txt" | oneline)")"

# ---------------------------------------------------------------------------------- absurd headers
# Each file is a few dozen bytes that declare up to the element limit; modelc runs with a small
# address space and must still stop with one error line (a reader that trusted the count would
# reserve gigabytes and die of std::bad_alloc or worse).
limit_kb=400000
lines OFF '50000000 50000000 0' '0 0 0' >"$d/absurd.off"
lines ply 'format ascii 1.0' 'element vertex 50000000' 'property float x' 'property float y' 'property float z' \
    'element face 50000000' 'property list uchar int vertex_indices' end_header '0 0 0' >"$d/absurd-ascii.ply"
{ lines ply 'format binary_little_endian 1.0' 'element vertex 50000000' 'property float x' 'property float y' 'property float z' \
    'element face 50000000' 'property list uint int vertex_indices' end_header; perl -e 'print pack("f<3", 0, 0, 0)'; } >"$d/absurd-bin.ply"
{ lines ply 'format binary_little_endian 1.0' 'element vertex 3' 'property float x' 'property float y' 'property float z' \
    'element face 1' 'property list uint int vertex_indices' end_header; perl -e 'print pack("f<9 L<", 0,0,0, 1,0,0, 0,1,0, 4000000000)'; } >"$d/absurd-list.ply"
perl -e 'print pack("a80 V", "binary", 50000000), pack("f<12 v", 0,0,1, 0,0,0, 1,0,0, 0,1,0, 0)' >"$d/absurd.stl"
lines 50000000 '0 0 0' '1 0 0' >"$d/absurd.xyz"
lines V1 50000000 '0 0 0' >"$d/absurd.cao"
lines V1 3 '0 0 0' '1 0 0' '0 1 0' 0 0 50000000 '3 0 1 2' >"$d/absurd-faces.cao"
for f in absurd.off absurd-ascii.ply absurd-bin.ply absurd-list.ply absurd.stl absurd.xyz absurd.cao absurd-faces.cao; do
    rc=0
    (ulimit -v $limit_kb && exec "$modelc" "$d/$f" -o "$tmp/out" --name absurd -q) 2>"$tmp/err.txt" >/dev/null || rc=$?
    n=$(awk 'END { print NR }' "$tmp/err.txt")
    if [ "$rc" = 1 ] && [ "$n" = 1 ] && grep -q "^modelc: $d/$f:\(byte \)\?[0-9]*: file ends" "$tmp/err.txt" && [ ! -e "$tmp/out/absurd" ]; then
        ok "$f ($(wc -c <"$d/$f") bytes) under ulimit -v $limit_kb: $(sed "s|^modelc: $d/||" "$tmp/err.txt")"
    else
        notok "$f under ulimit -v $limit_kb" "exit $rc, $n lines: $(head -c 300 "$tmp/err.txt" | oneline)"
    fi
done
# and a valid bake fits in that address space, so the limit above is not what made them fail
rc=0
(ulimit -v $limit_kb && exec "$modelc" "$d/plain.off" -o "$tmp/out" --name small --depth 5 -q) 2>"$tmp/err.txt" || rc=$?
check_cmd "a valid small bake runs under ulimit -v $limit_kb" test "$rc" = 0 -a -e "$tmp/out/small"
exit $((fails > 0))
