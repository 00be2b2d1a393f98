#!/usr/bin/env bash
# Input-validation tests for modelc. Every malformed input below must make modelc exit with
# status 1 (not a crash), print exactly one line "modelc: FILE:PLACE: MESSAGE" on stderr, and
# leave its output directory empty. PLACE is the 1-based line for text, "byte N" for binary data,
# absent for whole-file problems.
#
# usage: tests/gen/errors.sh [MODELC]        (default build/bin/modelc)
# Prints "ok - CASE" or "not ok - CASE: why" per case; exit status 0 only if all pass.
# The inputs are written here, into a temporary directory (binary ones with perl's pack).
set -u

MODELC=${1:-build/bin/modelc}
if [ ! -x "$MODELC" ]; then
    echo "not ok - setup: $MODELC is not an executable (build it with: make gen)"
    exit 1
fi
tmp=$(mktemp -d "${TMPDIR:-/tmp}/modelc-errors.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT
in=$tmp/in
mkdir -p "$in" "$tmp/out"
passed=0
failed=0

# Why the run of one case is wrong, or nothing if it is right.
judge() {
    local rc=$1 file=$2 place=$3 regex=$4 out=$5 prefix lines line msg
    if [ "$rc" -eq 0 ]; then echo "exit status 0, expected 1"; return; fi
    if [ "$rc" -eq 124 ]; then echo "timed out"; return; fi
    if [ "$rc" -ge 128 ]; then echo "crashed (exit status $rc)"; return; fi
    if [ "$rc" -ne 1 ]; then echo "exit status $rc, expected 1"; return; fi
    lines=$(awk 'END { print NR }' "$tmp/stderr")
    if [ "$lines" -ne 1 ]; then echo "stderr has $lines lines, expected 1: $(head -c 300 "$tmp/stderr" | tr '\n' '|')"; return; fi
    line=$(cat "$tmp/stderr")
    case $place in
        -) prefix="modelc: $file: " ;;
        *) prefix="modelc: $file:$place: " ;;
    esac
    if [ "${line#"$prefix"}" = "$line" ]; then echo "stderr '$line' does not start with '$prefix'"; return; fi
    msg=${line#"$prefix"}
    if ! [[ $msg =~ $regex ]]; then echo "message '$msg' does not match /$regex/"; return; fi
    if [ -n "$(ls -A "$out")" ]; then echo "output left in $out: $(ls -A "$out" | head -3 | tr '\n' ' ')"; return; fi
}

# expect CASE FILE PLACE REGEX: run modelc on FILE; PLACE is a line number, "byte N" or "-".
expect() {
    local name=$1 file=$2 place=$3 regex=$4 out=$tmp/out/$1 rc=0 why
    mkdir -p "$out"
    timeout 120 "$MODELC" "$file" -o "$out" --name model >"$tmp/stdout" 2>"$tmp/stderr" || rc=$?
    why=$(judge "$rc" "$file" "$place" "$regex" "$out")
    if [ -z "$why" ]; then
        echo "ok - $name"
        passed=$((passed + 1))
    else
        echo "not ok - $name: $why"
        failed=$((failed + 1))
    fi
}

size() { wc -c <"$1" | tr -d ' '; }

# A valid tetrahedron, the base most text cases are derived from.
TETRA_V=$'0 0 0\n1 0 0\n0 1 0\n0 0 1'
TETRA_F=$'3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3'

# ---------------------------------------------------------------------------------- any format

expect missing-file "$in/missing.off" - '^cannot open: No such file or directory$'
mkdir -p "$in/dir.off"
expect directory "$in/dir.off" - '^cannot open: Is a directory$'
printf 'OFF\n%s\n' "$TETRA_V" >"$in/model.txt"
expect unknown-extension "$in/model.txt" - "^unknown format '\.txt' \(expected \.off \.obj \.ply \.stl \.xyz \.cao \.gltf \.glb\)$"
: >"$in/empty.off"
expect empty-file "$in/empty.off" - '^file is empty$'

# ---------------------------------------------------------------------------------- OFF

f=$in/off-bad-header.off
printf 'OFX\n4 4 0\n%s\n%s\n' "$TETRA_V" "$TETRA_F" >"$f"
expect off-bad-header "$f" 1 "^expected an OFF header .*found 'OFX'$"

f=$in/off-binary.off
printf 'OFF BINARY\n' >"$f"
expect off-binary "$f" 1 '^binary OFF is not supported$'

f=$in/off-4d.off
printf '4OFF\n1 0 0\n0 0 0 1\n' >"$f"
expect off-not-3d "$f" 1 "^'4OFF' \(not 3D\) is not supported$"

f=$in/off-no-counts.off
printf 'OFF\n' >"$f"
expect off-no-counts "$f" 1 '^file ends before the vertex, face and edge counts$'

f=$in/off-two-counts.off
printf 'OFF\n4 4\n%s\n%s\n' "$TETRA_V" "$TETRA_F" >"$f"
expect off-two-counts "$f" 2 '^expected 3 counts \(vertices faces edges\), found 2 values$'

f=$in/off-negative-count.off
printf 'OFF\n-4 4 0\n%s\n%s\n' "$TETRA_V" "$TETRA_F" >"$f"
expect off-negative-count "$f" 2 '^negative number of vertices: -4$'

# 100 vertices promised, the file ends at line 40 after 37 (note the blank line 3).
f=$in/off-truncated-vertices.off
{ printf 'OFF\n100 10 0\n\n'; for i in $(seq 0 36); do echo "$i $((i % 5)) $((i % 3))"; done; } >"$f"
expect off-truncated-vertices "$f" 40 '^file ends after 37 of 100 vertices$'

f=$in/off-truncated-faces.off
printf 'OFF\n4 4 0\n%s\n3 0 2 1\n3 0 1 3\n' "$TETRA_V" >"$f"
expect off-truncated-faces "$f" 8 '^file ends after 2 of 4 faces$'

f=$in/off-extra-data.off
printf 'OFF\n4 4 0\n%s\n%s\n3 0 1 2\n' "$TETRA_V" "$TETRA_F" >"$f"
expect off-extra-data "$f" 11 '^extra data after the last face \(the header says 4 vertices, 4 faces\)$'

# The header's vertex count is one short: a vertex line is read as a face.
f=$in/off-count-too-small.off
printf 'OFF\n3 4 0\n%s\n%s\n' "$TETRA_V" "$TETRA_F" >"$f"
expect off-count-too-small "$f" 6 "^face has 2 vertex indices but its count says 0|^face has 0 vertices"

f=$in/off-vertex-values.off
printf 'OFF\n4 4 0\n0 0 0\n1 0\n0 1 0\n0 0 1\n%s\n' "$TETRA_F" >"$f"
expect off-vertex-values "$f" 4 '^expected 3 numbers per vertex, found 2$'

f=$in/off-face-short.off
printf 'OFF\n4 4 0\n%s\n3 0 2 1\n4 0 1 3\n3 0 3 2\n3 1 2 3\n' "$TETRA_V" >"$f"
expect off-face-fewer-indices "$f" 8 '^face has 3 vertex indices but its count says 4$'

f=$in/off-face-long.off
printf 'OFF\n4 4 0\n%s\n3 0 2 1 3\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' "$TETRA_V" >"$f"
expect off-face-more-indices "$f" 7 '^face count says 3 but 4 values follow'

f=$in/off-face-two.off
printf 'OFF\n4 4 0\n%s\n2 0 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' "$TETRA_V" >"$f"
expect off-face-two-vertices "$f" 7 '^face has 2 vertices \(at least 3 needed\)$'

f=$in/off-nan.off
printf 'OFF\n4 4 0\n0 0 0\n1 nan 0\n0 1 0\n0 0 1\n%s\n' "$TETRA_F" >"$f"
expect off-nan "$f" 4 "^coordinate is not finite: 'nan'$"

f=$in/off-inf.off
printf 'OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 -inf\n%s\n' "$TETRA_F" >"$f"
expect off-inf "$f" 6 "^coordinate is not finite: '-inf'$"

f=$in/off-overflow.off
printf 'OFF\n4 4 0\n0 0 0\n1 0 0\n0 1e400 0\n0 0 1\n%s\n' "$TETRA_F" >"$f"
expect off-overflow "$f" 5 "^coordinate is not finite: '1e400'$"

f=$in/off-non-numeric.off
printf 'OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 zero 1\n%s\n' "$TETRA_F" >"$f"
expect off-non-numeric "$f" 6 "^not a number: 'zero'$"

f=$in/off-index-range.off
{ printf 'OFF\n100 1 0\n'; for i in $(seq 0 99); do echo "$i $((i % 7)) $((i % 3))"; done; echo "3 0 1 120"; } >"$f"
expect off-index-out-of-range "$f" 103 '^vertex index 120 out of range \(0\.\.99\)$'

f=$in/off-index-negative.off
printf 'OFF\n4 4 0\n%s\n3 0 2 1\n3 0 -1 3\n3 0 3 2\n3 1 2 3\n' "$TETRA_V" >"$f"
expect off-index-negative "$f" 8 '^vertex index -1 out of range \(0\.\.3\)$'

f=$in/off-index-text.off
printf 'OFF\n4 4 0\n%s\n3 0 2 x\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' "$TETRA_V" >"$f"
expect off-index-not-integer "$f" 7 "^vertex index is not an integer: 'x'$"

# Huge counts are refused at the header line, before anything is allocated.
f=$in/off-too-many-vertices.off
printf 'OFF\n60000000 4 0\n%s\n%s\n' "$TETRA_V" "$TETRA_F" >"$f"
expect off-too-many-vertices "$f" 2 '^60000000 vertices exceed the limit of 50000000$'

f=$in/off-too-many-faces.off
printf 'OFF\n4 99999999999999999999 0\n%s\n%s\n' "$TETRA_V" "$TETRA_F" >"$f"
expect off-too-many-faces "$f" 2 '^99999999999999999999 faces exceed the limit of 50000000$'

# Comments and blank lines count as lines.
f=$in/off-comments.off
printf '# made by hand\nOFF\n# counts\n4 4 0\n\n0 0 0  # origin\n1 0 0\n0 1 0\n0 0 nan\n%s\n' "$TETRA_F" >"$f"
expect off-comments-line-numbers "$f" 9 "^coordinate is not finite: 'nan'$"

f=$in/off-color.off
printf 'COFF\n4 4 0\n0 0 0 255 0 0\n1 0 0 0 300 0\n0 1 0 0 0 255\n0 0 1 9 9 9\n%s\n' "$TETRA_F" >"$f"
expect off-colour-out-of-range "$f" 4 "^colour value '300' out of range \(0\.\.255\)$"

f=$in/off-no-vertices.off
printf 'OFF\n0 0 0\n' >"$f"
expect off-no-vertices "$f" - '^model has no vertices$'

f=$in/off-no-faces.off
printf 'OFF\n4 0 0\n%s\n' "$TETRA_V" >"$f"
expect off-no-faces "$f" - '^mesh has no faces$'

f=$in/off-zero-area.off
printf 'OFF\n4 2 0\n0 0 0\n1 1 1\n2 2 2\n3 3 3\n3 0 1 2\n3 1 2 3\n' >"$f"
expect off-zero-area "$f" - '^all 2 triangles have zero area$'

f=$in/off-identical-points.off
printf 'OFF\n4 4 0\n1 2 3\n1 2 3\n1 2 3\n1 2 3\n%s\n' "$TETRA_F" >"$f"
expect off-identical-points "$f" - '^all 4 triangles have zero area$'

f=$in/off-repeated-vertex.off
printf 'OFF\n4 2 0\n%s\n3 0 0 1\n4 1 2 2 3\n' "$TETRA_V" >"$f"
expect off-only-degenerate-faces "$f" - '^mesh has no usable faces'

# ---------------------------------------------------------------------------------- OBJ

OBJ_V=$'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1'

f=$in/obj-truncated.obj
printf '# tetra\n%s\nf 1 3 2\nf 1 2 4\nv 0.5 0.5\n' "$OBJ_V" >"$f"
expect obj-truncated "$f" 8 "^expected 3, 4 or 6 numbers after 'v' .*found 2$"

f=$in/obj-face-short.obj
printf '%s\nf 1 3 2\nf 1 2\n' "$OBJ_V" >"$f"
expect obj-face-two-vertices "$f" 6 '^face has 2 vertices \(at least 3 needed\)$'

f=$in/obj-nan.obj
printf 'v 0 0 0\nv 1 0 0\nv 0 NaN 0\nv 0 0 1\nf 1 3 2\n' >"$f"
expect obj-nan "$f" 3 "^coordinate is not finite: 'NaN'$"

f=$in/obj-non-numeric.obj
printf 'v 0 0 0\nv 1 0 0\nv 0 1,5 0\nv 0 0 1\nf 1 3 2\n' >"$f"
expect obj-non-numeric "$f" 3 "^not a number: '1,5'$"

f=$in/obj-index.obj
printf '%s\nvt 0 0\nf 1/1 2/1 9/1\n' "$OBJ_V" >"$f"
expect obj-index-out-of-range "$f" 6 '^vertex index 9 out of range \(1\.\.4\)$'

f=$in/obj-index-negative.obj
printf '%s\nf -1 -2 -5\n' "$OBJ_V" >"$f"
expect obj-negative-index-out-of-range "$f" 5 '^vertex index -5 out of range \(-4\.\.-1\)$'

f=$in/obj-index-zero.obj
printf '%s\nf 0 1 2\n' "$OBJ_V" >"$f"
expect obj-index-zero "$f" 5 '^vertex index 0 is invalid \(OBJ indices start at 1\)$'

f=$in/obj-bad-corner.obj
printf '%s\nf 1//1 2/x/1 3\n' "$OBJ_V" >"$f"
expect obj-bad-face-vertex "$f" 5 "^bad face vertex '2/x/1'$"

# A face may name vertices that come later in the file; one that never comes is reported at the face.
f=$in/obj-forward-index.obj
printf 'f 1 2 9\n%s\n' "$OBJ_V" >"$f"
expect obj-forward-index-out-of-range "$f" 1 '^vertex index 9 out of range \(1\.\.4\)$'

f=$in/obj-index-huge.obj
printf '%s\nf 1 2 99999999999999999999\n' "$OBJ_V" >"$f"
expect obj-index-beyond-limit "$f" 5 '^vertex index 99999999999999999999 exceeds the limit of 50000000$'

f=$in/obj-no-faces.obj
printf '%s\n' "$OBJ_V" >"$f"
expect obj-no-faces "$f" - '^mesh has no faces$'

f=$in/obj-too-many.obj
printf '%s\nf 1 2 3 4 5\n' "$OBJ_V" >"$f"
expect obj-index-past-end "$f" 5 '^vertex index 5 out of range \(1\.\.4\)$'

# ---------------------------------------------------------------------------------- PLY (ascii)

ply_header() {  # FORMAT VERTICES FACES
    printf 'ply\nformat %s 1.0\ncomment hand-written\nelement vertex %s\nproperty float x\nproperty float y\nproperty float z\nelement face %s\nproperty list uchar int vertex_indices\nend_header\n' "$1" "$2" "$3"
}

f=$in/ply-ascii-truncated.ply
{ ply_header ascii 4 4; printf '%s\n3 0 2 1\n' "$TETRA_V"; } >"$f"
expect ply-ascii-truncated "$f" 15 '^file ends after 1 of 4 faces$'

f=$in/ply-ascii-truncated-vertices.ply
{ ply_header ascii 8 4; printf '%s\n' "$TETRA_V"; } >"$f"
expect ply-ascii-truncated-vertices "$f" 14 '^file ends after 4 of 8 vertices$'

f=$in/ply-ascii-face-short.ply
{ ply_header ascii 4 4; printf '%s\n3 0 2 1\n3 0 1\n3 0 3 2\n3 1 2 3\n' "$TETRA_V"; } >"$f"
expect ply-ascii-face-fewer-indices "$f" 16 '^face has 2 vertex indices but its count says 3$'

f=$in/ply-ascii-vertex-long.ply
{ ply_header ascii 4 4; printf '0 0 0\n1 0 0 7\n0 1 0\n0 0 1\n%s\n' "$TETRA_F"; } >"$f"
expect ply-ascii-too-many-values "$f" 12 '^too many values for a vertex: expected 3, found 4$'

f=$in/ply-ascii-extra.ply
{ ply_header ascii 4 4; printf '%s\n%s\n3 0 1 2\n' "$TETRA_V" "$TETRA_F"; } >"$f"
expect ply-ascii-extra-data "$f" 19 "^extra data after the last element: '3'$"

f=$in/ply-ascii-nan.ply
{ ply_header ascii 4 4; printf '0 0 0\n1 0 0\n0 1 0\n0 0 inf\n%s\n' "$TETRA_F"; } >"$f"
expect ply-ascii-inf "$f" 14 "^coordinate is not finite: 'inf'$"

f=$in/ply-ascii-index.ply
{ ply_header ascii 4 4; printf '%s\n3 0 2 1\n3 0 1 9\n3 0 3 2\n3 1 2 3\n' "$TETRA_V"; } >"$f"
expect ply-ascii-index-out-of-range "$f" 16 '^vertex index 9 out of range \(0\.\.3\)$'

f=$in/ply-ascii-count-large.ply
{ ply_header ascii 60000000 4; printf '%s\n%s\n' "$TETRA_V" "$TETRA_F"; } >"$f"
expect ply-too-many-vertices "$f" 4 "^element 'vertex' count 60000000 exceeds the limit of 50000000$"

f=$in/ply-bad-magic.ply
{ printf 'plx\n'; ply_header ascii 4 4 | tail -n +2; } >"$f"
expect ply-bad-magic "$f" 1 "^expected 'ply' on the first line$"

f=$in/ply-bad-type.ply
printf 'ply\nformat ascii 1.0\nelement vertex 1\nproperty float16 x\nend_header\n0\n' >"$f"
expect ply-unknown-type "$f" 4 "^unknown property type 'float16'$"

f=$in/ply-colour-type.ply
printf 'ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nproperty double red\nend_header\n0 0 0 0.5\n' >"$f"
expect ply-colour-type "$f" 7 "^colour 'red' has type double \(must be uchar or float\)$"

f=$in/ply-face-first.ply
printf 'ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n3 0 1 2\n0 0 0\n1 0 0\n0 1 0\n' >"$f"
expect ply-face-before-vertex "$f" 3 "^the 'face' element must come after 'vertex'$"

f=$in/ply-no-end-header.ply
ply_header ascii 4 4 | head -n 8 >"$f"
expect ply-no-end-header "$f" 8 "^file ends inside the header \(no 'end_header'\)$"

f=$in/ply-points-identical.ply
{ ply_header ascii 3 0; printf '1 1 1\n1 1 1\n1 1 1\n'; } >"$f"
expect ply-points-identical "$f" - '^all 3 points are identical \(zero extent\)$'

f=$in/ply-no-points.ply
ply_header ascii 0 0 >"$f"
expect ply-no-points "$f" - '^point set has no points$'

# ---------------------------------------------------------------------------------- PLY (binary)

# Tetrahedron data, little endian: 4 x (3 float) then 4 x (uchar 3, 3 int).
VERTS_LE='pack("f<12", 0,0,0, 1,0,0, 0,1,0, 0,0,1)'
FACES_LE='pack("(C l<3)4", 3,0,2,1, 3,0,1,3, 3,0,3,2, 3,1,2,3)'
hdr=$(ply_header binary_little_endian 4 4 | wc -c | tr -d ' ')

f=$in/ply-bin-truncated.ply
{ ply_header binary_little_endian 4 4; perl -e "print $VERTS_LE, substr($FACES_LE, 0, 30)"; } >"$f"
expect ply-binary-truncated "$f" "byte $(size "$f")" '^file ends after 2 of 4 faces$'

f=$in/ply-bin-truncated-vertices.ply
{ ply_header binary_little_endian 4 4; perl -e "print substr($VERTS_LE, 0, 40)"; } >"$f"
expect ply-binary-truncated-vertices "$f" "byte $(size "$f")" '^file ends after 3 of 4 vertices$'

f=$in/ply-bin-extra.ply
{ ply_header binary_little_endian 4 4; perl -e "print $VERTS_LE, $FACES_LE, 'junk'"; } >"$f"
expect ply-binary-extra-data "$f" "byte $((hdr + 100))" '^4 bytes of extra data after the last element$'

f=$in/ply-bin-nan.ply  # y of vertex 2 is a quiet NaN
{ ply_header binary_little_endian 4 4; perl -e 'print pack("f<4 V f<7", 0,0,0, 1, 0x7fc00000, 0, 0,1,0, 0,0,1)' \
    -e "; print $FACES_LE"; } >"$f"
expect ply-binary-nan "$f" "byte $((hdr + 16))" '^coordinate is not finite \(nan\)$'

f=$in/ply-bin-index.ply
{ ply_header binary_little_endian 4 4; perl -e "print $VERTS_LE"';print pack("(C l<3)4", 3,0,2,1, 3,0,1,3, 3,0,7,2, 3,1,2,3)'; } >"$f"
expect ply-binary-index-out-of-range "$f" "byte $((hdr + 48 + 26 + 5))" '^vertex index 7 out of range \(0\.\.3\)$'

f=$in/ply-bin-big-endian.ply
{ ply_header binary_big_endian 4 4; perl -e 'print pack("f>12", 0,0,0, 1,0,0, 0,1,0, 0,0,1), pack("(C l>3)4", 3,0,2,1, 3,0,1,3, 3,0,3,2, 3,1,2,-3)'; } >"$f"
hdr_be=$(ply_header binary_big_endian 4 4 | wc -c | tr -d ' ')
expect ply-binary-big-endian-negative-index "$f" "byte $((hdr_be + 48 + 39 + 9))" '^vertex index -3 out of range \(0\.\.3\)$'

f=$in/ply-bin-face-count.ply
{ ply_header binary_little_endian 4 4; perl -e "print $VERTS_LE"';print pack("(C l<3)", 3,0,2,1), pack("C l<2", 2,0,1)'; } >"$f"
expect ply-binary-face-two-vertices "$f" "byte $((hdr + 48 + 13))" '^face has 2 vertices \(at least 3 needed\)$'

f=$in/ply-bin-count-large.ply
{ ply_header binary_little_endian 4 70000000; perl -e "print $VERTS_LE, $FACES_LE"; } >"$f"
expect ply-binary-too-many-faces "$f" 8 "^element 'face' count 70000000 exceeds the limit of 50000000$"

f=$in/ply-bin-points-truncated.ply  # a point set: no faces
{ ply_header binary_little_endian 5 0; perl -e "print $VERTS_LE"; } >"$f"
expect ply-binary-points-truncated "$f" "byte $(size "$f")" '^file ends after 4 of 5 vertices$'

# ---------------------------------------------------------------------------------- STL (binary)

TRI='pack("f<12 v", 0,0,1, 0,0,0, 1,0,0, 0,1,0, 0)'

f=$in/stl-bin-truncated.stl
perl -e "print pack('a80 V', 'binary', 4), $TRI, $TRI" >"$f"
expect stl-binary-truncated "$f" "byte 184" '^file ends after 2 of 4 triangles \(needs 284 bytes, has 184\)$'

f=$in/stl-bin-extra.stl
perl -e "print pack('a80 V', 'binary', 1), $TRI, $TRI" >"$f"
expect stl-binary-count-mismatch "$f" "byte 134" '^50 bytes of extra data after 1 triangles'

f=$in/stl-bin-short-header.stl
perl -e "print pack('a50', 'binary')" >"$f"
expect stl-binary-short-header "$f" "byte 50" '^file ends inside the 84-byte header'

f=$in/stl-bin-nan.stl  # second triangle, second corner, x
perl -e "print pack('a80 V', 'binary', 2), $TRI"'; print pack("f<6 V f<5 v", 0,0,1, 0,0,0, 0x7fc00000, 0,0, 0,1,0, 0)' >"$f"
expect stl-binary-nan "$f" "byte $((84 + 50 + 24))" '^coordinate is not finite \(nan\) in triangle 1$'

f=$in/stl-bin-count-large.stl
perl -e "print pack('a80 V', 'binary', 60000000), $TRI" >"$f"
expect stl-binary-too-many-triangles "$f" "byte 80" '^triangle count 60000000 exceeds the limit of 50000000$'

f=$in/stl-bin-empty.stl
perl -e "print pack('a80 V', 'solid but binary', 0)" >"$f"
expect stl-binary-no-triangles "$f" - '^mesh has no faces$'

f=$in/stl-bin-zero-area.stl
perl -e 'print pack("a80 V", "binary", 2); print pack("f<12 v", 0,0,0, 0,0,0, 1,1,1, 2,2,2, 0) for 1..2' >"$f"
expect stl-binary-zero-area "$f" - '^all 2 triangles have zero area$'

# ---------------------------------------------------------------------------------- STL (ascii)

facet() {  # three corners "x y z"
    printf '  facet normal 0 0 1\n    outer loop\n      vertex %s\n      vertex %s\n      vertex %s\n    endloop\n  endfacet\n' "$1" "$2" "$3"
}

f=$in/stl-ascii-truncated.stl
{ echo "solid t"; facet "0 0 0" "1 0 0" "0 1 0"; facet "0 0 0" "0 0 1" "1 0 0" | head -n 4; } >"$f"
expect stl-ascii-truncated "$f" 12 '^file ends inside facet 2$'

f=$in/stl-ascii-no-endsolid.stl
{ echo "solid t"; facet "0 0 0" "1 0 0" "0 1 0"; } >"$f"
expect stl-ascii-no-endsolid "$f" 8 "^file ends before 'endsolid' \(after 1 facets\)$"

f=$in/stl-ascii-four-corners.stl
{ echo "solid t"; facet "0 0 0" "1 0 0" "0 1 0" | sed '5a\      vertex 1 1 1'; echo "endsolid t"; } >"$f"
expect stl-ascii-four-vertices "$f" 7 '^facet has more than 3 vertices$'

f=$in/stl-ascii-two-corners.stl
{ echo "solid t"; facet "0 0 0" "1 0 0" "0 1 0" | sed '5d'; echo "endsolid t"; } >"$f"
expect stl-ascii-two-vertices "$f" 6 '^facet has 2 vertices, expected 3$'

f=$in/stl-ascii-nan.stl
{ echo "solid t"; facet "0 0 0" "1 0 0" "0 1 0"; facet "0 0 0" "0 0 1" "nan 0 0"; echo "endsolid t"; } >"$f"
expect stl-ascii-nan "$f" 13 "^coordinate is not finite: 'nan'$"

f=$in/stl-ascii-non-numeric.stl
{ echo "solid t"; facet "0 0 0" "1 0 0" "0 1 O"; echo "endsolid t"; } >"$f"
expect stl-ascii-non-numeric "$f" 6 "^not a number: 'O'$"

f=$in/stl-ascii-extra.stl
{ echo "solid t"; facet "0 0 0" "1 0 0" "0 1 0"; echo "endsolid t"; echo "vertex 1 2 3"; } >"$f"
expect stl-ascii-extra-data "$f" 10 "^extra data after 'endsolid': 'vertex'$"

f=$in/stl-ascii-keyword.stl
{ echo "solid t"; facet "0 0 0" "1 0 0" "0 1 0" | sed 's/endloop/end loop/'; echo "endsolid t"; } >"$f"
expect stl-ascii-bad-keyword "$f" 7 "^expected 'endloop', found 'end loop'$"

f=$in/stl-ascii-empty.stl
printf 'solid t\nendsolid t\n' >"$f"
expect stl-ascii-no-facets "$f" - '^mesh has no faces$'

# ---------------------------------------------------------------------------------- XYZ

f=$in/xyz-truncated.xyz
printf '10\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n' >"$f"
expect xyz-truncated "$f" 5 '^file ends after 4 of 10 points$'

f=$in/xyz-count-mismatch.xyz
printf '2\n0 0 0\n1 0 0\n0 1 0\n' >"$f"
expect xyz-more-than-announced "$f" 4 '^more points than the 2 announced on line 1$'

f=$in/xyz-partial-line.xyz
printf '0 0 0\n1 0 0\n0 1\n' >"$f"
expect xyz-partial-line "$f" 3 '^expected 3 or 6 numbers \(x y z \[nx ny nz\]\), found 2$'

f=$in/xyz-mixed.xyz
printf '0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0\n' >"$f"
expect xyz-mixed-columns "$f" 3 '^line has 3 numbers but earlier points have 6$'

f=$in/xyz-nan.xyz
printf '# points\n0 0 0\n1 0 0\n0 1 -nan\n' >"$f"
expect xyz-nan "$f" 4 "^coordinate is not finite: '-nan'$"

f=$in/xyz-normal-nan.xyz
printf '0 0 0 0 0 1\n1 0 0 0 nan 1\n' >"$f"
expect xyz-normal-nan "$f" 2 "^value is not finite: 'nan'$"

f=$in/xyz-non-numeric.xyz
printf '0 0 0\n1 0 0\n0x1 1 0\n' >"$f"
expect xyz-non-numeric "$f" 3 "^not a number: '0x1'$"

f=$in/xyz-count-large.xyz
printf '60000000\n0 0 0\n1 0 0\n' >"$f"
expect xyz-too-many-points "$f" 1 '^60000000 points exceed the limit of 50000000$'

f=$in/xyz-identical.xyz
printf '0.5 0.5 0.5\n0.5 0.5 0.5\n0.5 0.5 0.5\n' >"$f"
expect xyz-identical-points "$f" - '^all 3 points are identical \(zero extent\)$'

f=$in/xyz-comments-only.xyz
printf '# nothing here\n\n' >"$f"
expect xyz-no-points "$f" - '^point set has no points$'

# ---------------------------------------------------------------------------------- CAO

# ViSP's cube: line 1 the header, 2 the point count, 3-10 the points, 11 the 3D line count, 12 the
# count of faces from lines, 13 the count of faces from points, 14-19 the faces, 20 the cylinder
# count, 21 the circle count.
CAO_P=$'8\n0 0 0\n-1 0 0\n-1 1 0\n0 1 0\n0 0 1\n-1 0 1\n-1 1 1\n0 1 1'
CAO_F=$'6\n4 0 4 5 1\n4 1 5 6 2\n4 6 7 3 2\n4 3 7 4 0\n4 0 1 2 3\n4 7 6 5 4'
# The cube's 12 edges as 3D lines (lines 12-23 of a file with them) and its faces from them.
CAO_L=$'12\n0 4\n4 5\n5 1\n1 0\n5 6\n6 2\n2 1\n6 7\n7 3\n3 2\n7 4\n3 0'

f=$in/cao-bad-header.cao
printf '# cube\nW1\n%s\n0\n0\n%s\n0\n0\n' "$CAO_P" "$CAO_F" >"$f"
expect cao-bad-header "$f" 2 "^expected the version header V1, found 'W1'$"

f=$in/cao-no-header.cao
printf '%s\n0\n0\n%s\n0\n0\n' "$CAO_P" "$CAO_F" >"$f"
expect cao-no-header "$f" 1 "^expected the version header V1, found '8'$"

f=$in/cao-version.cao
printf 'V3\n%s\n0\n0\n%s\n0\n0\n' "$CAO_P" "$CAO_F" >"$f"
expect cao-unknown-version "$f" 1 "^version 'V3' is not supported \(V1 or V2\)$"

f=$in/cao-include.cao
printf 'V1\nload("parts/door.cao")\n%s\n0\n0\n%s\n0\n0\n' "$CAO_P" "$CAO_F" >"$f"
expect cao-include "$f" 2 '^includes \(load\(\.\.\.\)\) are not supported$'

f=$in/cao-include-first.cao
printf '# parts\nload("a.cao", t=[0; 0; 1])\nV1\n%s\n0\n0\n%s\n0\n0\n' "$CAO_P" "$CAO_F" >"$f"
expect cao-include-before-header "$f" 2 '^includes \(load\(\.\.\.\)\) are not supported$'

f=$in/cao-count.cao
printf 'V1\neight\n' >"$f"
expect cao-count-not-a-number "$f" 2 "^expected the number of points, found 'eight'$"

f=$in/cao-count-negative.cao
printf 'V1\n%s\n-2\n' "$CAO_P" >"$f"
expect cao-count-negative "$f" 11 '^negative number of 3D lines: -2$'

f=$in/cao-count-junk.cao
printf 'V1\n%s\n0 lines\n' "$CAO_P" >"$f"
expect cao-count-junk "$f" 11 "^unexpected 'lines' after the number of 3D lines$"

f=$in/cao-count-large.cao
printf 'V1\n60000000\n0 0 0\n' >"$f"
expect cao-too-many-points "$f" 2 '^60000000 points exceed the limit of 50000000$'

f=$in/cao-no-points.cao
printf 'V1\n0\n0\n0\n0\n' >"$f"
expect cao-no-points "$f" 2 '^number of points is 0'

f=$in/cao-truncated.cao
printf 'V1\n%s\n' "$CAO_P" | head -n 7 >"$f"
expect cao-truncated-points "$f" 7 '^file ends after 5 of 8 points$'

f=$in/cao-truncated-section.cao
printf 'V1\n%s\n0\n0\n# faces from points\n' "$CAO_P" >"$f"
expect cao-truncated-before-faces "$f" 13 '^file ends before the number of faces from points$'

f=$in/cao-point-values.cao
printf 'V1\n%s\n0\n0\n%s\n0\n0\n' "$CAO_P" "$CAO_F" | sed '5s/$/ 7/' >"$f"
expect cao-point-extra-value "$f" 5 '^expected 3 numbers per point \(x y z\), found 4$'

f=$in/cao-v2-point.cao
printf 'V2\n%s\n0\n0\n%s\n0\n0\n' "$CAO_P" "$CAO_F" >"$f"
expect cao-v2-without-image-coordinates "$f" 3 '^expected 5 values per point \(x y z i j\), found 3$'

f=$in/cao-nan.cao
printf 'V1\n%s\n0\n0\n%s\n0\n0\n' "$CAO_P" "$CAO_F" | sed '6s/^0/nan/' >"$f"
expect cao-nan "$f" 6 "^coordinate is not finite: 'nan'$"

f=$in/cao-line-index.cao
printf 'V1\n%s\n2\n0 1\n1 8\n0\n%s\n0\n0\n' "$CAO_P" "$CAO_F" >"$f"
expect cao-line-point-index-out-of-range "$f" 13 '^point index 8 out of range \(0\.\.7\)$'

f=$in/cao-line-same.cao
printf 'V1\n%s\n2\n0 1\n3 3 name=dot\n0\n%s\n0\n0\n' "$CAO_P" "$CAO_F" >"$f"
expect cao-line-names-a-point-twice "$f" 13 '^3D line names point 3 twice$'

f=$in/cao-line-short.cao
printf 'V1\n%s\n1\n0 name=half\n0\n%s\n0\n0\n' "$CAO_P" "$CAO_F" >"$f"
expect cao-line-one-index "$f" 12 '^3D line has 1 point index \(expected 2\)$'

f=$in/cao-face-index.cao
printf 'V1\n%s\n0\n0\n%s\n0\n0\n' "$CAO_P" "$CAO_F" | sed '16s/6/9/' >"$f"
expect cao-face-point-index-out-of-range "$f" 16 '^point index 9 out of range \(0\.\.7\)$'

f=$in/cao-face-line-index.cao
printf 'V1\n%s\n%s\n2\n4 0 1 2 3\n4 4 5 6 12\n0\n0\n0\n' "$CAO_P" "$CAO_L" >"$f"
expect cao-face-line-index-out-of-range "$f" 26 '^line index 12 out of range \(0\.\.11\)$'

f=$in/cao-face-no-lines.cao
printf 'V1\n%s\n0\n1\n3 0 1 2\n0\n0\n0\n' "$CAO_P" >"$f"
expect cao-face-line-index-without-lines "$f" 13 '^line index 0 out of range \(the file has no 3D lines\)$'

# lines 0 1 2 run 0-4-5-1 and line 4 (5-6) branches off at 5: the walk cannot close at 0 (the first
# point reported is the smallest)
f=$in/cao-not-a-loop.cao
printf 'V1\n%s\n%s\n1\n4 0 1 2 4\n0\n0\n0\n' "$CAO_P" "$CAO_L" >"$f"
expect cao-face-lines-not-a-loop "$f" 25 "^the face's lines do not form one closed loop \(point 0 ends 1 of them, not 2\)$"

# two triangles, 0-1-2 and 4-5-6, as one face: every point ends two lines, yet no single loop
f=$in/cao-two-loops.cao
printf 'V1\n%s\n6\n0 1\n1 2\n2 0\n4 5\n5 6\n6 4\n1\n6 0 1 2 3 4 5\n0\n0\n0\n' "$CAO_P" >"$f"
expect cao-face-lines-two-loops "$f" 19 "^the face's lines do not form one closed loop \(they form more than one\)$"

f=$in/cao-face-two.cao
printf 'V1\n%s\n0\n0\n%s\n0\n0\n' "$CAO_P" "$CAO_F" | sed '15s/.*/2 1 5/' >"$f"
expect cao-face-two-points "$f" 15 '^face has 2 points \(at least 3 needed\)$'

f=$in/cao-face-lines-two.cao
printf 'V1\n%s\n%s\n1\n2 0 1\n0\n0\n0\n' "$CAO_P" "$CAO_L" >"$f"
expect cao-face-two-lines "$f" 25 '^face has 2 lines \(at least 3 needed\)$'

f=$in/cao-face-short.cao
printf 'V1\n%s\n0\n0\n%s\n0\n0\n' "$CAO_P" "$CAO_F" | sed '14s/.*/4 0 4 5 name=front/' >"$f"
expect cao-face-fewer-indices "$f" 14 '^face has 3 point indices but its count says 4$'

f=$in/cao-face-long.cao
printf 'V1\n%s\n0\n0\n%s\n0\n0\n' "$CAO_P" "$CAO_F" | sed '14s/.*/3 0 4 5 1/' >"$f"
expect cao-face-more-indices "$f" 14 '^face count says 3 but 4 point indices follow$'

f=$in/cao-junk.cao
printf 'V1\n%s\n0\n0\n%s\n0\n0\n' "$CAO_P" "$CAO_F" | sed '17s/$/ junk/' >"$f"
expect cao-junk-after-face "$f" 17 "^expected key=value attributes after the face, found 'junk'$"

f=$in/cao-junk-line.cao
printf 'V1\n%s\n1\n0 1 // edge\n0\n%s\n0\n0\n' "$CAO_P" "$CAO_F" >"$f"
expect cao-junk-after-line "$f" 12 "^expected key=value attributes after the 3D line, found '//'$"

f=$in/cao-quote.cao
printf 'V1\n%s\n0\n0\n%s\n0\n0\n' "$CAO_P" "$CAO_F" | sed '18s/$/ name="bottom face/' >"$f"
expect cao-unclosed-quote "$f" 18 "^quoted value of 'name=\"bottom' has no closing quote$"

f=$in/cao-cylinder.cao
printf 'V1\n%s\n0\n0\n%s\n1\n0 6 0.5\n0\n' "$CAO_P" "$CAO_F" >"$f"
expect cao-cylinder "$f" 20 '^cylinders are not supported: modelc tracks lines and polygons$'

f=$in/cao-circle.cao
printf 'V1\n%s\n0\n0\n%s\n0\n# circles\n1\n0.5 0 1 3\n' "$CAO_P" "$CAO_F" >"$f"
expect cao-circle "$f" 22 '^circles are not supported: modelc tracks lines and polygons$'

f=$in/cao-extra.cao
printf 'V1\n%s\n0\n0\n%s\n0\n0\n4 0 1 2 3\n' "$CAO_P" "$CAO_F" >"$f"
expect cao-extra-data "$f" 22 "^extra data after the circles: '4'$"

f=$in/cao-no-faces.cao
printf 'V1\n%s\n1\n0 1\n0\n0\n' "$CAO_P" >"$f"
expect cao-no-faces "$f" - '^mesh has no faces$'

# ---------------------------------------------------------------------------------- summary

echo "# errors.sh: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
