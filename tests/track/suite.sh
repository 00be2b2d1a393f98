#!/usr/bin/env bash
# The edge-model bake (modelc --as edges) and the tracker front end (build/NAME/NAME-track):
#   - bakes: ViSP's cube.cao and fandisk (feature edges at two crease angles) dumped and compared with
#     a double-precision reading of the source (tests/track/edges_check.py: positions, lines, faces,
#     outward orientation); the generated files compile with -pedantic; budget.json's sums; the bake
#     errors (point set, a smooth mesh without lines, --unit, --fit, --stack-budget, over a budget)
#   - synthetic sequences with exact truth (tests/track/synth.c: clutter, noise, blur, a passing
#     occluder, a jump): the cube and fandisk, 3-DOF (orientation given) and 6-DOF, scored by
#     tests/track/errors.py (translation < 5 cm and rotation < 5 degrees), 6-DOF through a jump too
#   - ViSP's real cube sequence (Debian visp-images-data), all 218 frames: an estimate matching 85 % in
#     every frame, the same poses on a second run, overlays written (the poses against ViSP's own
#     tracker are make bench-track's)
#   - the front end's errors: one line, exit status 1 or 2, no CSV left behind
set -u
cd "$(dirname "$0")/../.." || exit 1
TAP_PREFIX="track: "
. tests/lib.sh
out=build/tests/track
fresh_dir "$out"
check() { check_problems "$@"; }
modelc=build/bin/modelc
mbt=/usr/share/visp-images-data/ViSP-images/mbt
cam2=273.86837875,271.0372029,169.10184970,117.00416725   # mbt/cube.xml's camera at 320x240
CC=${CC:-cc}

if [ ! -f "$mbt/cube.cao" ]; then
    notok "ViSP's cube" "$mbt/cube.cao missing: make deps installs visp-images-data"
    exit 1
fi
make -s build/cube/cube-track >"$out/make.log" 2>&1 || { notok "build build/cube/cube-track" "$(tail -n 5 "$out/make.log" | oneline)"; exit 1; }
track_obj=$(mkvar TRACK_OBJ)
rt_obj=$(rt_objs) || { notok "runtime objects"; exit 1; }

# bake NAME SOURCE OPTS...: an edge bake into $out, its tracker, its dump and its synth program
bake() {
    local name=$1 src=$2
    shift 2
    "$modelc" "$src" -o "$out" --name "$name" --as edges -q "$@" 2>"$out/$name.err" || { echo "modelc: $(oneline <"$out/$name.err")"; return 1; }
    $CC -std=c99 -pedantic -O2 -Wall -Wextra -Werror -Iruntime/include -ffunction-sections -fdata-sections \
        -o "$out/$name/$name-track" "$out/$name"/*.c $rt_obj $track_obj \
        -Wl,--gc-sections -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc,--wrap=free -lm 2>"$out/$name.cc" ||
        { echo "link: $(oneline <"$out/$name.cc")"; return 1; }
    local parts=("$out/$name/${name}_data_"*.c "$out/$name/${name}_edges.c" "$out/$name/${name}_model.c")
    $CC -std=c99 -O1 -Iruntime/include -DDUMP_MODEL="mc_model_$name" -o "$out/$name/dump" tests/track/edges_dump.c \
        "${parts[@]}" 2>>"$out/$name.cc" &&
        $CC -std=c99 -O2 -Iruntime/include -DSYNTH_MODEL="mc_model_$name" -o "$out/$name/synth" tests/track/synth.c \
            "${parts[@]}" -lm 2>>"$out/$name.cc" || { echo "tools: $(oneline <"$out/$name.cc")"; return 1; }
}

# ---- bakes against the source, in double precision ----------------------------------------------
fandisk=$(model_file fandisk) || { notok "fandisk" "cannot extract it (make models)"; exit 1; }
why=$(bake cube "$mbt/cube.cao") && { "$out/cube/dump" >"$out/cube.dump" || why="dump failed"; }
[ -z "$why" ] && why=$(python3 tests/track/edges_check.py "$out/cube.dump" "$mbt/cube.cao" 1 60 --convex | grep -v '^ok$')
check "cube.cao: 8 corners in um, its 12 polygon sides, 12 triangles facing out" "$why"
for a in 60 30; do
    why=$(bake "fandisk$a" "$fandisk" --unit 0.1 --crease-angle "$a") && { "$out/fandisk$a/dump" >"$out/fandisk$a.dump" || why="dump failed"; }
    [ -z "$why" ] && why=$(python3 tests/track/edges_check.py "$out/fandisk$a.dump" "$fandisk" 0.1 "$a" | grep -v '^ok$')
    check "fandisk at --crease-angle $a: the feature edges a double-precision reference finds, faces facing out" "$why"
done
n60=$(awk 'NR == 1 {print $3}' "$out/fandisk60.dump" 2>/dev/null)
n30=$(awk 'NR == 1 {print $3}' "$out/fandisk30.dump" 2>/dev/null)
check "a smaller crease angle tracks more lines ($n30 at 30, $n60 at 60 degrees)" \
    "$([ -n "$n60" ] && [ -n "$n30" ] && [ "$n30" -gt "$n60" ] || echo "$n30 against $n60")"
# --hide-faces: the same lines (by position), hidden by the mesh decimated to about that many faces, still closed
why=$(bake fandiskh "$fandisk" --unit 0.1 --hide-faces 2000) && { "$out/fandiskh/dump" >"$out/fandiskh.dump" || why="dump failed"; }
[ -z "$why" ] && why=$(python3 - "$out/fandisk60.dump" "$out/fandiskh.dump" <<'PYEOF'
import sys
def read(p):
    rows = [l.split() for l in open(p)]
    v = [tuple(r[1:]) for r in rows if r[0] == "v"]
    lines = sorted(tuple(sorted((v[int(r[1])], v[int(r[2])]))) for r in rows if r[0] == "l")
    return rows[0], lines, sum(r[0] == "f" for r in rows)
(_, full, nf), (head, hid, nh) = read(sys.argv[1]), read(sys.argv[2])
bad = []
if hid != full: bad.append("the lines differ from the full bake's")
if not 1500 <= nh <= 2000: bad.append("%d faces, not about 2000" % nh)
if head[4] != "1": bad.append("not closed")
print("; ".join(bad))
PYEOF
)
check "fandisk --hide-faces 2000: the full bake's lines, about 2000 closed hiding faces" "$why"
why=$(python3 - "$out/fandisk60/budget.json" <<'PYEOF'
import json, sys
b = json.load(open(sys.argv[1]))
f, r = b["flash"], b["ram"]
bad = []
if b["kind"] != "edge-model": bad.append("kind " + b["kind"])
if f["total"] != sum(f["arrays"].values()): bad.append("flash total is not the arrays' sum")
if f["image"] != f["total"] + f["descriptors"] + f["runtime_code"]["total"]: bad.append("flash image")
parts = ["color_buffer", "depth_buffer", "frame", "masks", "edge_scratch", "sdepth_bits", "sdepth_matched", "vertex_cache", "particles", "runtime_static"]
if r["image"] != sum(r[k] for k in parts): bad.append("ram image is not its parts' sum")
if r["vertex_cache"] != 16 * b["vertices"] or r["particles"] != 2 * 40 * r["particle_count"]: bad.append("cache or particles")
if r["frame"] != b["screen"][0] * b["screen"][1]: bad.append("frame")
print("; ".join(bad))
PYEOF
)
check "budget.json: flash and RAM are the sums of their parts" "$why"

# ---- bake errors: one line, exit status 1 or 2, no output -----------------------------------------
kitten=$(model_file kitten)
bunny=$(model_file bunny00)
bad_bake() {   # NAME STATUS REGEX FILE OPTS...
    local name=$1 want=$2 re=$3 file=$4 rc=0 o=$out/bad
    shift 4
    fresh_dir "$o"
    "$modelc" "$file" -o "$o" --name m --as edges "$@" >"$out/bad.out" 2>"$out/bad.err" || rc=$?
    local lines msg
    lines=$(wc -l <"$out/bad.err")
    msg=$(cat "$out/bad.err")
    if [ "$rc" -ne "$want" ]; then notok "$name" "exit status $rc, expected $want: $(oneline <"$out/bad.err")"
    elif [ "$lines" -ne 1 ] || ! [[ $msg =~ ^modelc:\ .*$re ]]; then notok "$name" "stderr: $(oneline <"$out/bad.err")"
    elif [ -n "$(ls -A "$o")" ]; then notok "$name" "output left: $(ls -A "$o" | oneline)"
    else ok "$name"; fi
}
bad_bake "a point set: no faces" 1 "point set cannot be baked as an edge model" "$kitten"
bad_bake "a smooth mesh: no line to track" 1 "no edge to track" "$bunny"
bad_bake "--unit furlong" 2 "--unit furlong" "$fandisk" --unit furlong
bad_bake "--unit -1" 2 "--unit -1" "$fandisk" --unit -1
bad_bake "--fit is refused" 2 "--fit" "$fandisk" --flash-budget 1M --fit
bad_bake "over --stack-budget (the tracker's bound)" 1 "over budget: stack" "$fandisk" --stack-budget 1K
bad_bake "over --ram-budget" 1 "over budget: ram" "$mbt/cube.cao" --ram-budget 64K
bad_bake "too large for micrometres" 1 "beyond \+-268 m" "$fandisk" --unit 1000

# ---- synthetic sequences ----------------------------------------------------------------------
# run NAME BAKE FRAMES SYNTH-OPTS -- TRACK-OPTS: a sequence rendered, tracked, scored
run() {
    local name=$1 b=$2 frames=$3
    shift 3
    local so=() to=()
    while [ $# -gt 0 ] && [ "$1" != -- ]; do so+=("$1"); shift; done
    shift
    to=("$@")
    fresh_dir "$out/$name"
    "$out/$b/synth" --out "$out/$name" --frames "$frames" "${so[@]}" 2>"$out/$name.err" &&
        "$out/$b/$b-track" --frames "$out/$name/image%04d.pgm" --camera "$cam2" --init "$out/$name/init.pos" \
            --out "$out/$name/poses.csv" "${to[@]}" 2>>"$out/$name.err" || { echo "failed: $(oneline <"$out/$name.err")"; return 1; }
}
score() {   # NAME [errors.py options]: prints errors.py's line
    python3 tests/track/errors.py "$out/$1/truth.csv" "$out/$1/poses.csv" "${@:2}"
}
field() { echo "$1" | tr ' ' '\n' | sed -n "s/^$2=//p"; }
# at least RATE of the frames succeed (with a jump: of those outside the re-detection), and
# re-detection within 30 frames
judge() {   # CHECK-NAME NAME MIN-RATE [--jump K]
    local line why="" rate
    if ! line=$(score "$2" "${@:4}"); then check "$1" "errors.py failed"; return; fi
    rate=$(field "$line" rate)
    [ $# -gt 3 ] && rate=$(field "$line" tracked_rate)
    awk -v r="$rate" -v m="$3" 'BEGIN { exit !(r >= m) }' || why="rate below $3"
    if [ $# -gt 3 ]; then
        local d
        d=$(field "$line" redetect)
        { [ "$d" -ge 0 ] && [ "$d" -le 30 ]; } || why="$why${why:+; }re-detection after $d frames"
    fi
    echo "$2: $line" >>"$out/figures.txt"
    check "$1 ($line)" "$why"
}
why=$(run cube3 cube 80 --jump 40 --occlude 10:25 --seed 3 -- --orientation "$out/cube3/orientation.txt" --search 100)
[ -n "$why" ] && notok "cube, 3-DOF" "$why" || judge "cube, 3-DOF, clutter, noise, blur, an occluder, a jump at 40: >= 95 % tracked, re-detected within 30" cube3 0.95 --jump 40
# 6-DOF through a jump of 25 degrees and 5 cm: found again by the image search (detect.h)
why=$(run cube6j cube 80 --jump 40 --jump-turn -20,15,0 --occlude 10:25 --seed 3 -- --search 100)
[ -n "$why" ] && notok "cube, 6-DOF, a jump" "$why" || judge "cube, 6-DOF, clutter, noise, blur, an occluder, a jump at 40: >= 95 % tracked, re-detected within 30" cube6j 0.95 --jump 40
why=$(run cube6 cube 80 --occlude 30:45 --seed 4 -- --radius 1 --search 100)
[ -n "$why" ] && notok "cube, 6-DOF" "$why" || judge "cube, 6-DOF, clutter, noise, blur, an occluder: >= 95 %" cube6 0.95
why=$(run fandisk3 fandisk60 40 --start 0,0,0.45,0.4,0.6,0.2 --jump 20 --occlude 5:12 --seed 5 -- --orientation "$out/fandisk3/orientation.txt" --search 100 --particles 150 --layers 1 --step-t 3)
[ -n "$why" ] && notok "fandisk, 3-DOF" "$why" || judge "fandisk (12,946 faces), 3-DOF, a jump at 20: >= 95 % tracked, re-detected within 30" fandisk3 0.95 --jump 20

# ---- ViSP's real cube sequence ------------------------------------------------------------------
real() {   # CSV OPTS...
    local csv=$1
    shift
    build/cube/cube-track --frames "$mbt/cube/image%04d.pgm" --camera "$mbt/cube.xml" --init "$mbt/cube.0.pos" \
        --scale 2 --out "$csv" "$@" 2>"$out/real.err"
}
fresh_dir "$out/overlay"
if real "$out/real1.csv" --overlay "$out/overlay" && real "$out/real2.csv"; then
    why=$(python3 - "$out/real1.csv" <<'PYEOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
bad = []
if len(rows) != 218: bad.append("%d frames, not 218" % len(rows))
low = [r["frame"] for r in rows if float(r["confidence"]) < 0.85]
if low: bad.append("confidence below 0.85 at frames " + ",".join(low[:10]))
print("; ".join(bad))
PYEOF
)
    # how close the poses come to ViSP's own tracker is make bench-track's (tests/bench/RESULTS.md)
    check "the real cube, 218 frames at 320x240: an estimate with confidence >= 0.85 in every frame (matched over visible line pixels)" "$why"
    check "the real cube: the same poses on a second run" \
        "$(cmp -s <(cut -d, -f1-10 "$out/real1.csv") <(cut -d, -f1-10 "$out/real2.csv") || echo "the runs differ")"
    n=$(find "$out/overlay" -name 'frame*.png' | wc -l)
    sig=$(head -c 8 "$out/overlay/frame0100.png" 2>/dev/null | od -An -tx1 | tr -d ' \n')
    check "the real cube: an overlay PNG a frame" "$([ "$n" -eq 218 ] && [ "$sig" = 89504e470d0a1a0a ] || echo "$n PNGs, signature $sig")"
else
    notok "the real cube sequence" "$(oneline <"$out/real.err")"
fi

# ---- the front end's errors ---------------------------------------------------------------------
bad_run() {   # NAME STATUS REGEX OPTS...
    local name=$1 want=$2 re=$3 rc=0
    shift 3
    rm -f "$out/bad.csv" "$out/bad.csv.tmp"
    build/cube/cube-track --out "$out/bad.csv" "$@" >"$out/bad.out" 2>"$out/bad.err" || rc=$?
    local msg
    msg=$(cat "$out/bad.err")
    if [ "$rc" -ne "$want" ]; then notok "$name" "exit status $rc, expected $want: $(oneline <"$out/bad.err")"
    elif [ "$(wc -l <"$out/bad.err")" -ne 1 ] || ! [[ $msg =~ ^cube-track:\ .*$re ]]; then notok "$name" "stderr: $(oneline <"$out/bad.err")"
    elif [ -e "$out/bad.csv" ] || [ -e "$out/bad.csv.tmp" ]; then notok "$name" "a CSV was left"
    else ok "$name"; fi
}
F=("--frames" "$mbt/cube/image%04d.pgm")
bad_run "no --init" 2 "required" "${F[@]}" --camera "$mbt/cube.xml"
bad_run "a pattern without a number" 2 "--frames" --frames "$mbt/cube/image.pgm" --camera "$mbt/cube.xml" --init "$mbt/cube.0.pos"
bad_run "a camera of three numbers" 1 "camera" "${F[@]}" --camera 1,2,3 --init "$mbt/cube.0.pos"
bad_run "a pose file that is not there" 1 "cannot open" "${F[@]}" --camera "$mbt/cube.xml" --init "$out/none.pos"
bad_run "more particles than the bake holds" 2 "--particles" "${F[@]}" --camera "$mbt/cube.xml" --init "$mbt/cube.0.pos" --particles 5000
bad_run "an unknown option" 2 "unknown option" "${F[@]}" --camera "$mbt/cube.xml" --init "$mbt/cube.0.pos" --colour red
bad_run "a search grid of 0 pixels" 2 "--detect-stride 0" "${F[@]}" --camera "$mbt/cube.xml" --init "$mbt/cube.0.pos" --detect-stride 0
bad_run "a search confidence above 1.01" 2 "--detect-below 2" "${F[@]}" --camera "$mbt/cube.xml" --init "$mbt/cube.0.pos" --detect-below 2
head -c 1000 "$mbt/cube/image0003.pgm" >"$out/cut.pgm"
mkdir -p "$out/cut"
for k in 0 1 2; do cp "$mbt/cube/image000$k.pgm" "$out/cut/f$k.pgm"; done
cp "$out/cut.pgm" "$out/cut/f3.pgm"
bad_run "a truncated frame mid-sequence: no CSV" 1 "f3.pgm" --frames "$out/cut/f%d.pgm" --camera "$mbt/cube.xml" --init "$mbt/cube.0.pos"
# the tracker's own shrinking by 2 (its own loop, without a division) against the firmware data
# script's box average in Python: the same frames give the same poses
python3 runtime/front/fw/track_frames.py --frames "$mbt/cube/image%04d.pgm" --camera "$mbt/cube.xml" \
    --init "$mbt/cube.0.pos" --count 4 --screen 320x240 --scale 2 --particles 100 --c "$out/k2.c" --pgm "$out/k2" \
    >"$out/k2.log" 2>&1
build/cube/cube-track "${F[@]}" --camera "$mbt/cube.xml" --init "$mbt/cube.0.pos" --count 4 --scale 2 \
    --out "$out/k2a.csv" --fixed-out "$out/k2a.txt" 2>"$out/k2a.err"
build/cube/cube-track --frames "$out/k2/image%04d.pgm" --shrunk 2 --camera "$mbt/cube.xml" --init "$mbt/cube.0.pos" \
    --count 4 --out "$out/k2b.csv" --fixed-out "$out/k2b.txt" 2>"$out/k2b.err"
check "--scale 2 shrinks 640x480 frames as the Python box average does: the same 4 poses" \
    "$([ -s "$out/k2a.txt" ] && [ "$(wc -l <"$out/k2a.txt")" -eq 4 ] && cmp -s "$out/k2a.txt" "$out/k2b.txt" ||
        echo "$(oneline <"$out/k2.log") $(oneline <"$out/k2a.err") $(diff "$out/k2a.txt" "$out/k2b.txt" 2>&1 | head -2 | oneline)")"
# the benchmark's comparer with a third party's scores (visp_track --judge's CSV): four frames, A
# 2 cm off B in frames 2 and 3 only; A scored lower in frames 0 and 3
{
    echo "frame,tx,ty,tz,tux,tuy,tuz"
    for k in 0 1 2 3; do echo "$k,0,0,$([ "$k" -ge 2 ] && echo 0.52 || echo 0.5),0,0,0"; done
} >"$out/cmp_a.csv"
printf 'frame,tx,ty,tz,tux,tuy,tuz\n0,0,0,0.5,0,0,0\n1,0,0,0.5,0,0,0\n2,0,0,0.5,0,0,0\n3,0,0,0.5,0,0,0\n' >"$out/cmp_b.csv"
printf 'frame,error\n0,9\n1,12\n2,15\n3,8\n' >"$out/cmp_a.judge.csv"
printf 'frame,error\n0,10\n1,11\n2,14\n3,20\n' >"$out/cmp_b.judge.csv"
cmp_out=$(python3 tests/bench/cube_compare.py "$out/cmp_a.csv" "$out/cmp_b.csv" --quiet --names A,B \
    --judged "$out/cmp_a.judge.csv,$out/cmp_b.judge.csv" 2>&1)
check "cube_compare --judged: the medians, A's lower scores in all frames and in those outside 1 cm" \
    "$(grep -qx 'judged: median A 10.50, B 12.50; A lower in 2 of 4' <<<"$cmp_out" &&
       grep -qx 'judged outside 1 cm and 3 deg: A lower in 1 of 2' <<<"$cmp_out" || oneline <<<"$cmp_out")"
printf 'frame,error\n0,9\n1,12\n' >"$out/cmp_short.csv"
cmp_out=$(python3 tests/bench/cube_compare.py "$out/cmp_a.csv" "$out/cmp_b.csv" --quiet \
    --judged "$out/cmp_short.csv,$out/cmp_b.judge.csv" 2>&1)
cmp_rc=$?
check "cube_compare --judged: a score file missing a frame is one error line, exit 1" \
    "$([ "$cmp_rc" -eq 1 ] && [ "$(wc -l <<<"$cmp_out")" -eq 1 ] && grep -q 'no score for frame 2' <<<"$cmp_out" || echo "exit $cmp_rc: $(oneline <<<"$cmp_out")")"
# an output that is not a regular file (a pipe here; /dev/null alike) is written into, never
# replaced by a renamed file
rm -f "$out/pipe" "$out/pipe.txt" && mkfifo "$out/pipe"
cat "$out/pipe" >"$out/pipe.txt" &
reader=$!
build/cube/cube-track "${F[@]}" --camera "$mbt/cube.xml" --init "$mbt/cube.0.pos" --count 2 --out "$out/pipe" 2>"$out/pipe.err"
rc=$?
wait "$reader"
check "--out into a pipe: the pipe stays a pipe and gets the CSV" \
    "$([ "$rc" -eq 0 ] && [ -p "$out/pipe" ] && [ "$(wc -l <"$out/pipe.txt")" -eq 3 ] || echo "exit $rc, $(ls -l "$out/pipe" | cut -c1), $(wc -l <"$out/pipe.txt") lines: $(oneline <"$out/pipe.err")")"
exit $status
