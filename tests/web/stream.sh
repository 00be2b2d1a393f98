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
exit $status
