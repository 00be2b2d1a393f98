#!/usr/bin/env bash
# --views (hidden-cell removal at bake time): bad specs, the share of cells removed, frontal images
# byte-identical to the unpruned bake's (several sizes, depth D and D-1, finishing on and off),
# point sets, budget.json and determinism.
set -u
cd "$(dirname "$0")/../.."
modelc=${1:-build/bin/modelc}
TAP_PREFIX="views: "
. tests/lib.sh
out=build/views-test
fresh_dir "$out"
nok() { notok "$1"; }
check() { check_cmd "$@"; }   # check NAME COMMAND...

# bad specs: one error line, exit status 2, nothing written
for spec in "" "front" "front:abc" "front:200" "front:-5" "all,front:30" "front:60@0" "1:2:3:4" "yaw:10" "front:60,"; do
    "$modelc" build/models/bunny00.off -o "$out/bad" -q --views "$spec" 2>"$out/err.txt" >/dev/null
    status=$?
    lines=$(wc -l <"$out/err.txt")
    if [ "$status" -eq 2 ] && [ "$lines" -eq 1 ] && grep -q '^modelc: --views' "$out/err.txt" && [ ! -e "$out/bad" ]; then
        ok "--views '$spec' is refused with one line and status 2"
    else
        nok "--views '$spec': status $status, $lines lines: $(head -c 200 "$out/err.txt")"
    fi
done

# a viewer for one bake, linked like the Makefile's link_view (its runtime and front-end objects)
view_objs=$(rt_objs host | tr '\n' ' ')
view_cc="$(mkvar CC) $(mkvar CFLAGS) $(mkvar RT_CFLAGS)"
view_ld=$(mkvar VIEW_LDFLAGS)
link() {
    # shellcheck disable=SC2086
    $view_cc -o "$1/view" "$1"/*.c $view_objs $view_ld
}
# frontal images of two bakes, byte for byte: sizes x depths x finishing
same_front() {
    local a=$1 b=$2 depth=$3 bad=0
    for size in 320x240 640x480 97x61 256x256; do
        for d in "$depth" $((depth - 1)); do
            for fin in "" --no-finish; do
                "$a/view" --ppm "$a/f.ppm" --size $size --depth $d $fin >/dev/null &&
                    "$b/view" --ppm "$b/f.ppm" --size $size --depth $d $fin >/dev/null &&
                    cmp -s "$a/f.ppm" "$b/f.ppm" || { echo "# differs: $size depth $d $fin"; bad=1; }
            done
        done
    done
    return $bad
}
# share of the first image's drawn pixels that differ in the second (the corner pixel is background)
differ() {
    python3 - "$1" "$2" <<'PY'
import sys
def read(p):
    parts = open(p, 'rb').read().split(b'\n', 3)
    return parts[3]
a, b = read(sys.argv[1]), read(sys.argv[2])
bg = a[:3]
px = [(a[i:i+3], b[i:i+3]) for i in range(0, len(a), 3)]
drawn = sum(1 for p, q in px if p != bg)
print("%.2f" % (100.0 * sum(1 for p, q in px if p != q) / drawn))
PY
}
field() { python3 -c "import json,sys; b=json.load(open('$1/budget.json')); print(eval(sys.argv[1]))" "$2"; }

# bunny00: --views front:60 against the unpruned bake
"$modelc" build/models/bunny00.off -o "$out" --name full -q
start=$(date +%s.%N)
"$modelc" build/models/bunny00.off -o "$out" --name f60 --views front:60 2>"$out/f60.txt"
secs=$(echo "$(date +%s.%N) - $start" | bc)
check "the bake reports its pruning on one line" test "$(grep -c '^modelc: --views front:60: removed [0-9]* of [0-9]* cells' "$out/f60.txt")" -eq 1
pct=$(field "$out/f60" "round(100.0 * b['pruning']['cells_removed'] / b['pruning']['cells_before'], 1)")
echo "# bunny00 --views front:60: $pct % of cells removed in $secs s: $(cat "$out/f60.txt")"
check "bunny00 --views front:60 removes at least 30 % of the cells ($pct %)" \
    python3 -c "import sys; sys.exit(not $pct >= 30)"
check "budget.json records the pruning and counts agree" python3 - "$out/full" "$out/f60" <<'PY'
import json, sys
full = json.load(open(sys.argv[1] + "/budget.json"))
b = json.load(open(sys.argv[2] + "/budget.json"))
p = b["pruning"]
assert "pruning" not in full
assert p["views"] == "front:60" and p["directions"] == 400, p
assert p["cells_before"] == full["points"], (p, full["points"])
assert b["points"] == p["cells_before"] - p["cells_removed"], (b["points"], p)
assert all(x <= y for x, y in zip(b["points_per_level"], full["points_per_level"]))
assert b["palette_entries"] == full["palette_entries"]
PY
if link "$out/full" && link "$out/f60"; then
    check "bunny00 front:60: frontal images byte-identical (4 sizes, depth 8 and 7, finish on and off)" \
        same_front "$out/full" "$out/f60" 8
    for view in "30 0" "0 30" "-45 20"; do
        set -- $view
        "$out/full/view" --ppm "$out/t1.ppm" --yaw $1 --pitch $2 >/dev/null
        "$out/f60/view" --ppm "$out/t2.ppm" --yaw $1 --pitch $2 >/dev/null
        d=$(differ "$out/t1.ppm" "$out/t2.ppm")
        check "bunny00 front:60 turned to yaw $1 pitch $2: $d % of the drawn pixels differ (< 3)" \
            python3 -c "import sys; sys.exit(not $d < 3)"
    done
else
    nok "bunny00 viewers build"
fi
# --views all is the default: byte-identical to a bake without it
"$modelc" build/models/bunny00.off -o "$out/all" --name full -q --views all
check "--views all changes nothing" diff -r "$out/full" "$out/all/full" -x view -x f.ppm

# determinism, and -q: the same bake again, quiet (one bake for both checks)
check "-q silences the pruning line" \
    test -z "$("$modelc" build/models/bunny00.off -o "$out/again" --name f60 -q --views front:60 2>&1)"
check "same input and --views give byte-identical output" diff -r "$out/f60" "$out/again/f60" -x view -x f.ppm

# a direction list: yaw:pitch and cones around them
"$modelc" build/models/bunny00.off -o "$out" --name list -q --views "0:0,30:10,-30:0:15@40"
check "a list of directions prunes too" test "$(field "$out/list" "b['pruning']['cells_removed'] > 0 and b['pruning']['directions'] == 42")" = True

# a point set: splatted, prunes, same frontal image
"$modelc" build/models/kitten.xyz -o "$out" --name kfull -q --depth 7
"$modelc" build/models/kitten.xyz -o "$out" --name k20 -q --depth 7 --views front:20
kpct=$(field "$out/k20" "round(100.0 * b['pruning']['cells_removed'] / b['pruning']['cells_before'], 1)")
echo "# kitten --views front:20: $kpct % of cells removed"
check "kitten --views front:20 removes cells ($kpct %)" python3 -c "import sys; sys.exit(not $kpct > 5)"
if link "$out/kfull" && link "$out/k20"; then
    check "kitten front:20: frontal images byte-identical (depth 7 and 6)" same_front "$out/kfull" "$out/k20" 7
else
    nok "kitten viewers build"
fi
"$modelc" build/models/kitten.xyz -o "$out/again" --name k20 -q --depth 7 --views front:20
check "point sets prune deterministically" diff -r "$out/k20" "$out/again/k20" -x view -x f.ppm

[ "$fails" -eq 0 ]
