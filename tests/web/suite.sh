#!/usr/bin/env bash
# The web viewer (runtime/front/web, make web): the module's imports and exports, then the page in
# headless Chromium, from file:// and from a plain static server, driven through its own handlers
# (tests/web/drive.js, evaluated through tests/web/cdp.py in real time): the view it ends at follows from the events, the frames while it moves are
# coarse, and its fine frame equals the native viewer's PPM for the same view, pixel for pixel.
# The stream page has its own suite (tests/web/stream.sh), and so do a mesh bake's pages (there: its
# bake has a stream too). Chromium missing is a failure (make deps installs it);
# Chromium present but unable to start is a skip with its reason.
set -u
cd "$(dirname "$0")/../.."
TAP_PREFIX="web: "
. tests/lib.sh
# build.sh's compiles through the shared object cache (tests/cc_cached.sh): the runtime's wasm
# objects are the same for every page the web suites build
export WASM_CC="$PWD/tests/cc_cached.sh clang"

dir=build/tests/web
rm -rf "$dir" && mkdir -p "$dir"
name=bunny00
view=build/$name/$name-view
[ -x "$view" ] || { notok "the native viewer $view is built (tests/run.sh builds it)"; exit 1; }

# ---- the module ----
if make -s --no-print-directory build/$name/web/index.html >"$dir/build.log" 2>&1; then
    ok "make build/$name/web/index.html builds build/$name/web/ from the bake"
else
    notok "make build/$name/web/index.html" "$(tail -n 5 "$dir/build.log" | oneline)"
    exit 1
fi
web=build/$name/web
problems=""
for f in index.html viewer.js $name.wasm $name.wasm.js; do [ -s "$web/$f" ] || problems+="$f missing; "; done
for f in stream.html $name-stream.wasm $name.mcs; do [ ! -e "$web/$f" ] || problems+="$f, but the bake has no stream; "; done
check_problems "build/$name/web/ holds index.html, viewer.js, $name.wasm and $name.wasm.js (no stream page: the bake has no stream)" "$problems"
{
    python3 tests/web/wasm_info.py "$web/$name.wasm"
    python3 -c 'import base64, sys; print("base64-same", base64.b64decode(open(sys.argv[2]).read().split(chr(34))[1]) == open(sys.argv[1], "rb").read())' \
        "$web/$name.wasm" "$web/$name.wasm.js"
} >"$dir/module.txt" 2>&1
imports=$(sed -n 's/^imports //p' "$dir/module.txt")
[ "$imports" = 0 ] && ok "$name.wasm imports nothing ($(sed -n 's/^bytes //p' "$dir/module.txt") bytes)" ||
    notok "$name.wasm imports nothing" "$(oneline <"$dir/module.txt")"
exports=$(sed -n 's/^exports //p' "$dir/module.txt")
problems=""
for e in memory mcw_draw mcw_rgba mcw_drawn mcw_drawn_depth mcw_depth mcw_max_width mcw_max_height; do
    [[ " $exports " == *" $e "* ]] || problems+="$e; "
done
check_problems "$name.wasm exports its memory and the mcw_* functions viewer.js calls" "$problems"
[ "$(sed -n 's/^base64-same //p' "$dir/module.txt")" = True ] && ok "$name.wasm.js holds the module's bytes" ||
    notok "$name.wasm.js holds the module's bytes" "$(oneline <"$dir/module.txt")"

# ---- the page in Chromium ----
command -v chromium >/dev/null || { notok "chromium is installed (make deps)"; exit 1; }
cdp() { timeout 120 python3 tests/web/cdp.py "$@"; }   # URL [--eval JS | --eval-file F]: prints the value as JSON
if ! cdp about:blank --eval '6 * 7' >"$dir/blank.txt" 2>&1 || [ "$(cat "$dir/blank.txt")" != 42 ]; then
    for c in "file: drive" "file: fine frame" "http: drive" "http: fine frame" "http: fetch" "bad page"; do
        skip "$c" "Chromium cannot start here: $(head -n 3 "$dir/blank.txt" | oneline)"
    done
    exit 0
fi

# what the driver's events must lead to (viewer.js: 8 angle units a pixel of drag, 64 a key press,
# zoom times 1.1 a wheel notch, angles modulo 4096): drag (+49, -5), a notch in, one ArrowRight
expect_yaw=$(( (49 * 8 + 64) % 4096 )) expect_pitch=$(( ((-5 * 8) % 4096 + 4096) % 4096 ))
expect_zoom=$(python3 -c 'print(round(65536 * 1.1))')
page=$dir/page
cp -r "$web" "$page"

# run_page URL TAG: loads the page, checks the driver's result against the native viewer
run_page() {
    local url=$1 tag=$2 out=$dir/$2
    mkdir -p "$out"
    cdp "$url" --eval-file tests/web/drive.js >"$out/drive.json" 2>"$out/drive.err"
    python3 - "$out/drive.json" "$out" <<'EOF' >"$out/result.txt" 2>&1
import base64, json, sys
try:
    r = json.load(open(sys.argv[1]))
except ValueError:
    print('error no result from the page'); sys.exit(0)
w, h = r['width'], r['height']
rgba = base64.b64decode(r['rgba'])
rgb = bytes(b for i, b in enumerate(rgba) if i % 4 != 3)
open(sys.argv[2] + '/canvas.ppm', 'wb').write(b'P6\n%d %d\n255\n' % (w, h) + rgb)
print('alpha', 'opaque' if all(rgba[i] == 255 for i in range(3, len(rgba), 4)) else 'not opaque')
print('size %dx%d' % (w, h))
v = r['view']
print('view', v['yaw'], v['pitch'], v['zoom'], v['error'])
for k, f in enumerate(r['moving']):
    print('moving%d' % k, f['yaw'], f['pitch'], f['zoom'], f['error'], int(f['moving']), f['depth'])
f = r['rest']
print('rest', f['yaw'], f['pitch'], f['zoom'], f['error'], int(f['moving']), f['depth'], f['points'])
EOF
    if grep -q '^error' "$out/result.txt"; then
        notok "$tag: drive" "$(cat "$out/result.txt" "$out/drive.err" | head -c 300 | oneline)"
        notok "$tag: fine frame" "no result"
        return
    fi
    read -r _ yaw pitch zoom err < <(grep '^view' "$out/result.txt")
    read -r _ size < <(grep '^size' "$out/result.txt")
    problems=""
    [ "$yaw $pitch $zoom" = "$expect_yaw $expect_pitch $expect_zoom" ] ||
        problems+="view yaw $yaw pitch $pitch zoom $zoom, expected $expect_yaw $expect_pitch $expect_zoom; "
    [ "$err" = 16 ] || problems+="bound $err, expected 16 (one pixel); "
    while read -r _ my mp mz me mm md; do   # each moving frame: twice the bound, the native depth there
        [ "$me" = 32 ] && [ "$mm" = 1 ] || problems+="a moving frame drew at bound $me (moving $mm), expected 32; "
        nd=$("$view" --size "$size" --yaw "$(python3 -c "print($my * 360 / 4096)")" --pitch "$(python3 -c "print($mp * 360 / 4096)")" \
            --zoom "$(python3 -c "print($mz / 65536)")" --error 2 --ppm /dev/null | sed -n 's/.* depth \([0-9]*\) .*/\1/p')
        [ "$md" = "$nd" ] || problems+="a moving frame drew depth $md, the native viewer $nd at 2 px; "
    done < <(grep '^moving' "$out/result.txt")
    grep -q '^alpha opaque' "$out/result.txt" || problems+="canvas not opaque; "
    check_problems "$tag: drive: drag, wheel and key reach the view (yaw $yaw pitch $pitch zoom $zoom), coarse frames while moving" "$problems"
    # the native viewer's frame for the view the page ended at
    "$view" --size "$size" --yaw "$(python3 -c "print($yaw * 360 / 4096)")" --pitch "$(python3 -c "print($pitch * 360 / 4096)")" \
        --zoom "$(python3 -c "print($zoom / 65536)")" --ppm "$out/native.ppm" >"$out/native.txt" 2>&1
    if cmp -s "$out/native.ppm" "$out/canvas.ppm"; then
        ok "$tag: fine frame at ${size}: the canvas equals the native viewer's PPM pixel for pixel ($(sed -n 's/.*points \([0-9]*\).*/\1/p' "$out/native.txt") points)"
    else
        notok "$tag: fine frame at ${size}" "$(python3 tests/bench/bench_tools.py image-cmp "$out/native.ppm" "$out/canvas.ppm" 2>&1 | oneline)"
    fi
}

run_page "file://$PWD/$page/index.html" "file"

# from a plain static server; without NAME.wasm.js, so the page must fetch NAME.wasm
served=$dir/served
cp -r "$page" "$served"
rm -f "$served/$name.wasm.js"
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
python3 -m http.server "$port" --bind 127.0.0.1 --directory "$served" >"$dir/http.log" 2>&1 &
server=$!
trap 'kill $server 2>/dev/null' EXIT
for _ in $(seq 50); do python3 -c "import urllib.request; urllib.request.urlopen('http://127.0.0.1:$port/index.html')" 2>/dev/null && break; sleep 0.1; done
run_page "http://127.0.0.1:$port/index.html" "http"
grep -q "GET /$name.wasm " "$dir/http.log" && ok "http: fetch: the page fetched $name.wasm from the server" ||
    notok "http: fetch: the page fetched $name.wasm from the server" "$(oneline <"$dir/http.log")"
kill $server 2>/dev/null

# a page whose module cannot load says so in its status line
bad=$dir/bad
cp -r "$web" "$bad"
rm -f "$bad/$name.wasm.js"
cdp "file://$PWD/$bad/index.html" --eval \
    "window.modelc.ready.then(() => 'loaded', () => document.getElementById('status').textContent)" >"$dir/bad.txt" 2>&1
[ "$(cat "$dir/bad.txt")" = "\"$name: cannot load $name.wasm.js\"" ] &&
    ok "bad page: a module that cannot load gives one status line naming it" ||
    notok "bad page: a module that cannot load gives one status line naming it" "$(oneline <"$dir/bad.txt")"

exit $status
