#!/usr/bin/env bash
# The web viewer's stream page (runtime/front/web: stream.html, NAME-stream.wasm; make web WEB_STREAM=1)
# for bunny00 baked at depth 7 with --emit stream: the module holds no bake and imports nothing; then
# the page in headless Chromium (tests/web/stream_check.py: one browser, a local server that also
# sends the stream cut, damaged or level by level with pauses) against the native viewer linked with
# the same bake: the whole stream, driven; cuts at random and at every level's end; flipped bytes,
# a wrong version, trailing bytes; progressive drawing while the fetch goes on. tests/run.sh
# runs it beside tests/web/suite.sh. Chromium missing is a failure; Chromium unable to
# start is a skip with its reason (stream_check.py).
set -u
cd "$(dirname "$0")/../.."
TAP_PREFIX="web: stream: "
. tests/lib.sh
# build.sh's compiles through the shared object cache (tests/cc_cached.sh): the runtime's wasm
# objects are the same for every page the web suites build
export WASM_CC="$PWD/tests/cc_cached.sh clang"

dir=build/tests/web-stream
fresh_dir "$dir"
name=bunny
bake=$dir/$name
model=$(model_file bunny00) || { notok "bunny00's model file (make models)"; exit 1; }
if build/bin/modelc "$model" -o "$dir" --name $name --depth 7 --screen 320x240 --emit stream -q >"$dir/bake.log" 2>&1 &&
    runtime/front/web/build.sh "$dir" $name >"$dir/build.log" 2>&1; then
    ok "build.sh on a bake with --emit stream writes stream.html, $name-stream.wasm and $name.mcs beside the page"
else
    notok "bake and build.sh" "$(cat "$dir/bake.log" "$dir/build.log" | tail -n 5 | oneline)"
    exit 1
fi
web=$bake/web
problems=""
for f in index.html viewer.js $name.wasm $name.wasm.js stream.html $name-stream.wasm $name.mcs; do
    [ -s "$web/$f" ] || problems+="$f missing; "
done
cmp -s "$web/$name.mcs" "$bake/$name.mcs" || problems+="$name.mcs is not the bake's; "
grep -q "data-stream=\"$name.mcs\"" "$web/stream.html" || problems+="stream.html names no stream; "
check_problems "web/ holds both pages, and $name.mcs is the bake's stream" "$problems"

# the modules' imports, exports and sizes
{
    python3 tests/web/wasm_info.py "$web/$name-stream.wasm" | grep -v "^bytes "
    echo "bytes $(stat -c %s "$web/$name-stream.wasm") $(stat -c %s "$web/$name.wasm") $(stat -c %s "$bake/$name.mcs")"
} >"$dir/module.txt" 2>&1
imports=$(sed -n 's/^imports //p' "$dir/module.txt")
exports=$(sed -n 's/^exports //p' "$dir/module.txt")
read -r sbytes bbytes mcs < <(sed -n 's/^bytes //p' "$dir/module.txt")
problems=""
[ "$imports" = 0 ] || problems+="imports: $(oneline <"$dir/module.txt"); "
for e in memory mcw_draw mcw_rgba mcw_drawn mcw_drawn_depth mcw_depth mcw_max_width mcw_max_height mcw_scratch \
    mcw_scratch_bytes mcw_feed mcw_end mcw_stream_len mcw_stream_total mcw_stream_levels mcw_stream_error \
    mcw_stream_error_at mcw_stream_error_name; do
    [[ " $exports " == *" $e "* ]] || problems+="no export $e; "
done
[[ " $exports " != *" mcw_name "* ]] || problems+="exports mcw_name (the bake's); "
# the bake's arrays are about the stream's size: the stream module must be smaller by most of it
[ -n "$sbytes" ] && [ $((bbytes - sbytes)) -ge $((mcs * 3 / 4)) ] ||
    problems+="$name-stream.wasm $sbytes bytes, the baked $name.wasm $bbytes: not smaller by 3/4 of the stream's $mcs; "
check_problems "$name-stream.wasm imports nothing, exports the stream's functions, holds no bake ($sbytes bytes; the baked page's $name.wasm $bbytes, the stream $mcs)" "$problems"

# the native viewer of the same bake, linked as the Makefile's link_view
view_objs=$(rt_objs host | tr '\n' ' ')
view_cc="$(mkvar CC) $(mkvar CFLAGS) $(mkvar RT_CFLAGS)"
view_ld=$(mkvar VIEW_LDFLAGS)
# shellcheck disable=SC2086
if ! $view_cc -o "$bake/$name-view" "$bake"/*.c $view_objs $view_ld >"$dir/view.log" 2>&1; then
    notok "the native viewer of the bake links" "$(oneline <"$dir/view.log")"
    exit 1
fi

# ---- the page in Chromium ----
command -v chromium >/dev/null || { notok "chromium is installed (make deps)"; exit 1; }
mkdir -p "$dir/out"
timeout 150 python3 tests/web/stream_check.py "$web" "$bake/$name-view" "$bake/budget.json" "$dir/out" \
    --seed 12 --drive tests/web/drive.js >"$dir/check.txt" 2>"$dir/check.err"
rc=$?
cat "$dir/check.txt"
# its checks print their own lines; a crash, a timeout or a traceback is one more failure
if [ -s "$dir/check.err" ] || { [ $rc -ne 0 ] && ! grep -q '^not ok' "$dir/check.txt"; }; then
    notok "stream_check.py ran to its end" "exit $rc: $(tail -n 3 "$dir/check.err" | oneline)"
fi
[ $rc -eq 0 ] || status=1

# ---- a mesh bake's pages: the baked one's mesh modes, the stream one's mesh drawn as it comes ----
# fandisk --as both at depth 6 with packed splits (creases among its lines; a bake of half a second);
# its stream page served by a plain static server with a copy cut
# between two of the mesh's records (its adjacency not come): the whole stream in lines at 3,000
# vertices, and the cut one in lines (drawn shaded, at the last level that came), each against the
# native viewer of the same bake (--mode lines --lod 3000; --stream CUT --mode lines)
mname=fmesh
mbake=$dir/$mname
# shellcheck disable=SC2086
if build/bin/modelc "$(model_file fandisk)" -o "$dir" --name $mname --depth 6 --screen 320x240 --as both --emit stream \
    --stream-splits packed -q >"$dir/mesh-bake.log" 2>&1 && runtime/front/web/build.sh "$dir" $mname >>"$dir/mesh-bake.log" 2>&1 &&
    $view_cc -o "$mbake/$mname-view" "$mbake"/*.c $view_objs $view_ld >>"$dir/mesh-bake.log" 2>&1; then
    ok "mesh: fandisk baked --as both --emit stream --stream-splits packed, its pages and native viewer built"
else
    notok "mesh: fandisk baked --as both --emit stream --stream-splits packed, its pages and native viewer built" \
        "$(tail -n 5 "$dir/mesh-bake.log" | oneline)"
    exit 1
fi
mweb=$mbake/web
# the baked page (index.html) of the same bake: opened in lines at 3,000 vertices from its address,
# then m and [ (shaded+lines at half the splits above the base), then an arrow key
exports=$(python3 tests/web/wasm_info.py "$mweb/$mname.wasm" | sed -n 's/^exports //p')
problems=""
for e in mcw_draw_mesh mcw_mesh_vertices mcw_mesh_base_vertices mcw_mesh_cap mcw_mesh_lines_ready mcw_mesh_level \
    mcw_mesh_faces mcw_mesh_drawn mcw_mesh_line_pixels mcw_mesh_refused; do
    [[ " $exports " == *" $e "* ]] || problems+="$e; "
done
check_problems "mesh: $mname.wasm exports the mesh functions viewer.js calls" "$problems"
mkdir -p "$dir/baked"
timeout 120 python3 tests/web/cdp.py "file://$PWD/$mweb/index.html?mode=lines&lod=3000" --eval-file tests/web/mesh.js \
    >"$dir/baked/mesh.json" 2>"$dir/baked/mesh.err"
python3 tests/web/mesh_check.py "$dir/baked/mesh.json" "$mbake/$mname-view" "$dir/baked" >"$dir/baked/result.txt" 2>&1
base=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["pmesh"]["base_vertices"])' "$mbake/budget.json")
half=$((base + (3000 - base) / 2))
got=$(grep '^frame' "$dir/baked/result.txt" | awk '{printf "%s %s %s / ", $3, $4, $6}')
check_problems "mesh: the baked page ?mode=lines&lod=3000 draws lines at 3,000 vertices; m then [ draw shaded+lines at $half (half the splits above the base); an arrow key turns it; the help line names the keys" \
    "$([ "$got" = "lines 3000 0 / shaded+lines $half 0 / shaded+lines $half 64 / " ] && grep -q '^help True' "$dir/baked/result.txt" ||
        echo "$(oneline <"$dir/baked/result.txt") $(head -c 200 "$dir/baked/mesh.err" | oneline)")"
for k in 0 1 2; do
    read -r _ _ mk lk fk yk sk < <(grep "^frame $k " "$dir/baked/result.txt")
    check_problems "mesh: the baked page's frame $k (${mk:-?}, level ${lk:-?}, ${fk:-?} faces, yaw ${yk:-?}): the canvas equals the native viewer's --mode ${mk:-?} --lod ${lk:-?} PPM pixel for pixel" \
        "$([ "${sk:-}" = same ] || python3 tests/bench/bench_tools.py image-cmp "$dir/baked/native$k.ppm" "$dir/baked/canvas$k.ppm" 2>&1 | oneline)"
done
read -r cut cut_level < <(python3 -c '
import json, sys
m = json.load(open(sys.argv[1]))["stream"]["mesh_levels"]
print(m[2]["at"] + 5, m[2]["level"])' "$mbake/budget.json")
head -c "$cut" "$mbake/$mname.mcs" >"$mweb/cut.mcs"
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
python3 -m http.server "$port" --bind 127.0.0.1 --directory "$mweb" >"$dir/mesh-http.log" 2>&1 &
server=$!
trap 'kill $server 2>/dev/null' EXIT
for _ in $(seq 50); do python3 -c "import urllib.request; urllib.request.urlopen('http://127.0.0.1:$port/stream.html')" 2>/dev/null && break; sleep 0.1; done
# mesh_page TAG QUERY NATIVE-ARGS...: the page's frame at rest against the native viewer's PPM
mesh_page() {
    local tag=$1 query=$2
    shift 2
    timeout 120 python3 tests/web/cdp.py "http://127.0.0.1:$port/stream.html?$query" --eval-file tests/web/stream_mesh.js \
        >"$dir/mesh-$tag.json" 2>"$dir/mesh-$tag.err"
    python3 - "$dir/mesh-$tag.json" "$dir/mesh-$tag.canvas.ppm" <<'PY' >"$dir/mesh-$tag.txt" 2>&1
import json, sys
sys.path.insert(0, 'tests/web')
from mesh_check import canvas_ppm
try:
    r = json.load(open(sys.argv[1]))
except ValueError:
    print('error no result from the page'); sys.exit(0)
canvas_ppm(r, r['rgba'], sys.argv[2])
s, f = r['stream'], r['rest'] or {}
print('state', int(s['ok']), s['meshLevel'], s['meshLines'], f.get('mode'), f.get('level'), int(bool(f.get('shadedOnly'))))
print('status', r['status'].replace('\n', ' | '))
PY
    "$mbake/$mname-view" --size 320x240 "$@" --ppm "$dir/mesh-$tag.native.ppm" >"$dir/mesh-$tag.native.txt" 2>&1
    read -r _ sok slevel slines fmode flevel fshaded < <(grep '^state' "$dir/mesh-$tag.txt")
    same=$(cmp -s "$dir/mesh-$tag.canvas.ppm" "$dir/mesh-$tag.native.ppm" && echo same ||
        python3 tests/bench/bench_tools.py image-cmp "$dir/mesh-$tag.native.ppm" "$dir/mesh-$tag.canvas.ppm" 2>&1 | oneline)
}
vertices=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["pmesh"]["vertices"])' "$mbake/budget.json")
mesh_page whole "mode=lines&lod=3000" --mode lines --lod 3000
check_problems "mesh: the whole stream (?mode=lines&lod=3000): complete, the mesh's $vertices levels and its adjacency came, lines drawn at 3,000 vertices, the canvas equal to the native viewer's --mode lines --lod 3000" \
    "$([ "${sok:-} ${slevel:-} ${slines:-} ${fmode:-} ${flevel:-} ${fshaded:-}" = "1 $vertices 1 lines 3000 0" ] && [ "$same" = same ] ||
        echo "$(oneline <"$dir/mesh-whole.txt") $(head -c 200 "$dir/mesh-whole.err" | oneline); image: $same")"
mesh_page cut "stream=cut.mcs&mode=lines" --stream "$mweb/cut.mcs" --mode lines
check_problems "mesh: cut at byte $cut, between mesh records (?stream=cut.mcs&mode=lines): truncated, level $cut_level the finest drawn, shaded (no adjacency), as the native viewer's --stream of the cut file in lines" \
    "$([ "${sok:-} ${slevel:-} ${slines:-} ${fmode:-} ${flevel:-} ${fshaded:-}" = "0 $cut_level 0 lines $cut_level 1" ] && [ "$same" = same ] &&
        grep -q "truncated at byte $cut" "$dir/mesh-cut.txt" ||
        echo "$(oneline <"$dir/mesh-cut.txt") $(head -c 200 "$dir/mesh-cut.err" | oneline); image: $same")"
# another bake's stream whose mesh has more vertices than this page's mesh memory, the stream itself
# within its buffer (lion_head at 13,000 faces, points at depth 1): its points drawn, the mesh refused
# in the status line, as the native viewer refuses it
vmax=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["pmesh"]["vertices"])' "$mbake/budget.json")
build/bin/modelc "$(model_file lion_head)" -o "$dir/big" --name big --depth 1 --screen 320x240 --as both --max-faces 13000 --emit stream \
    --stream-splits packed -q >"$dir/big.log" 2>&1
cp "$dir/big/big/big.mcs" "$mweb/big.mcs" 2>/dev/null
read -r bbuf bverts < <(python3 -c 'import json, sys; b = json.load(open(sys.argv[1]))
print(b["stream"]["buffer"], b["pmesh"]["vertices"])' "$dir/big/big/budget.json" 2>/dev/null)
timeout 120 python3 tests/web/cdp.py "http://127.0.0.1:$port/stream.html?stream=big.mcs&mode=shaded" \
    --eval-file tests/web/stream_mesh.js >"$dir/mesh-big.json" 2>"$dir/mesh-big.err"
python3 -c 'import json, sys
r = json.load(open(sys.argv[1])); f = r["rest"] or {}
print(int(r["stream"]["ok"]), f.get("mode"), f.get("depth"), r["status"].replace("\n", " | "))' "$dir/mesh-big.json" >"$dir/mesh-big.txt" 2>&1
"$mbake/$mname-view" --stream "$mweb/big.mcs" --mode shaded --ppm /dev/null >/dev/null 2>"$dir/mesh-big.native.err"
check_problems "mesh: another bake's stream ($bverts vertices; its buffer ${bbuf:-?} bytes, within this page's $(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["stream"]["buffer"])' "$mbake/budget.json")) in shaded: its points drawn, the mesh refused in the status line, as the native viewer refuses it" \
    "$([ "${bverts:-0}" -gt "$vmax" ] && grep -q "^1 points 1 .*its mesh ($bverts vertices) is larger than this page's mesh memory: points only" "$dir/mesh-big.txt" &&
        grep -q "larger than this viewer's mesh buffers" "$dir/mesh-big.native.err" ||
        echo "$(oneline <"$dir/mesh-big.txt") $(head -c 200 "$dir/mesh-big.err" | oneline) native: $(oneline <"$dir/mesh-big.native.err")")"
kill $server 2>/dev/null
exit $status
