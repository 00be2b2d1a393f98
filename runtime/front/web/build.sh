#!/usr/bin/env bash
# Builds the web viewer of a bake: build.sh BUILD NAME [WxH]
#   BUILD/NAME/ holds the bake (modelc -o BUILD --name NAME); writes BUILD/NAME/web/:
#   NAME.wasm     the runtime, the bake and web.c; clang --target=wasm32 -nostdlib, wasm-ld; no imports
#   NAME.wasm.js  the same bytes in base64, for pages opened from file:// (which cannot fetch)
#   viewer.js     the page's script; index.html the page, its canvas WxH (default: the bake's screen
#                 up to 640x480)
# and when the bake has a stream (modelc --emit stream: NAME.mcs), the stream page besides:
#   stream.html   the same page receiving the model as a stream over fetch (http(s) only)
#   NAME-stream.wasm  the runtime, web.c and a receive buffer of MC_NAME_STREAM_BYTES; no bake
#   NAME.mcs      the stream it fetches (stream.html?stream=URL fetches another)
# The folder is replaced whole or not at all: everything is written beside it and renamed at the end.
# WASM_CC: the compiler command (default clang; words split on spaces, e.g. a caching wrapper
# before it, as the tests use tests/cc_cached.sh).
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 BUILD NAME [WxH]" >&2; exit 2; }
build=$1 name=$2 size=${3:-}
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
bake=$build/$name
header=$bake/$name.h
die() { echo "modelc web: $*" >&2; exit 1; }
[ -f "$header" ] || die "$header: no bake named $name under $build (run modelc -o $build --name $name first)"
read -ra wasm_cc <<<"${WASM_CC:-clang}"
command -v "${wasm_cc[0]}" >/dev/null || die "${wasm_cc[0]} not found (make deps installs clang and lld)"
command -v wasm-ld >/dev/null || command -v wasm-ld-14 >/dev/null || die "wasm-ld not found (make deps installs lld)"

up=$(echo "$name" | tr 'a-z' 'A-Z')
sw=$(sed -n "s/^#define MC_${up}_SCREEN_WIDTH \([0-9]*\)$/\1/p" "$header")
sh=$(sed -n "s/^#define MC_${up}_SCREEN_HEIGHT \([0-9]*\)$/\1/p" "$header")
[ -n "$sw" ] && [ -n "$sh" ] || die "$header: no MC_${up}_SCREEN_WIDTH / HEIGHT"
if [ -n "$size" ]; then
    [[ $size =~ ^([0-9]+)x([0-9]+)$ ]] || die "size $size: expected WxH"
    w=${BASH_REMATCH[1]} h=${BASH_REMATCH[2]}
    [ "$w" -ge 1 ] && [ "$h" -ge 1 ] && [ "$w" -le "$sw" ] && [ "$h" -le "$sh" ] || die "size $size: not within the bake's screen ${sw}x${sh}"
else
    w=$(( sw < 640 ? sw : 640 )) h=$(( sh < 480 ? sh : 480 ))
fi

out=$bake/web
tmp=$(mktemp -d "$bake/.web.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
# -nostdlib: no libc and no compiler runtime; the runtime needs neither (freestanding, no heap).
# Each source is compiled once, $(nproc) at a time, and the modules link the objects they need.
cflags=(--target=wasm32 -nostdlib -O2 -std=c99 -ffreestanding -Wall -Wextra -Werror -I"$root/runtime/include")
# shellcheck disable=SC2054
ldflags=(--target=wasm32 -nostdlib -Wl,--no-entry -Wl,--gc-sections -Wl,--strip-all)
jobs_max=$(nproc 2>/dev/null || echo 2)
mkdir -p "$tmp/.o/rt" "$tmp/.o/bake"
compile() {   # SRC OBJ [FLAGS...], in the background; a failure leaves $tmp/.o/failed
    while [ "$(jobs -rp | wc -l)" -ge "$jobs_max" ]; do wait -n || true; done
    { "${wasm_cc[@]}" "${cflags[@]}" "${@:3}" -c -o "$2" "$1" || touch "$tmp/.o/failed"; } &
}
stream_bytes=$(sed -n "s/^#define MC_${up}_STREAM_BYTES \([0-9]*\)$/\1/p" "$header")
if [ -f "$bake/$name.mcs" ]; then
    [ -n "$stream_bytes" ] || die "$header: no MC_${up}_STREAM_BYTES beside $name.mcs (bake again with --emit stream)"
    # a bake with a mesh part: the stream module keeps its level-of-detail memory too
    mesh_defs=()
    pv=$(sed -n "s/^#define MC_${up}_PMESH_VERTICES \([0-9]*\)$/\1/p" "$header")
    if [ -n "$pv" ]; then
        mesh_defs=(-DMC_WEB_PMESH_VERTICES="$pv"
            -DMC_WEB_PMESH_LOD_BYTES="$(sed -n "s/^#define MC_${up}_PMESH_LOD_BYTES \([0-9]*\)$/\1/p" "$header")"
            -DMC_WEB_PMESH_FACING_BYTES="$(sed -n "s/^#define MC_${up}_PMESH_FACING_BYTES \([0-9]*\)$/\1/p" "$header")")
    fi
    compile "$root/runtime/front/web/web.c" "$tmp/.o/web-stream.o" -DMC_WEB_MAX_PIXELS="($sw * $sh)" \
        -DMC_WEB_MAX_WIDTH="$sw" -DMC_WEB_MAX_HEIGHT="$sh" -DMC_WEB_STREAM_BYTES="$stream_bytes" "${mesh_defs[@]}"
fi
compile "$root/runtime/front/web/web.c" "$tmp/.o/web.o" -DMC_WEB_MAX_PIXELS="($sw * $sh)"
rt_objs=("$tmp/.o/rgb.o" "$tmp/.o/mesh_frame.o") bake_objs=()
compile "$root/runtime/front/common/rgb.c" "$tmp/.o/rgb.o"
compile "$root/runtime/front/common/mesh_frame.c" "$tmp/.o/mesh_frame.o"
for c in "$root"/runtime/src/*.c; do
    rt_objs+=("$tmp/.o/rt/$(basename "$c" .c).o")
    compile "$c" "${rt_objs[-1]}"
done
for c in "$bake"/*.c; do
    bake_objs+=("$tmp/.o/bake/$(basename "$c" .c).o")
    compile "$c" "${bake_objs[-1]}"
done
wait
[ ! -e "$tmp/.o/failed" ] || die "compiling for wasm32 failed (above)"
"${wasm_cc[@]}" "${ldflags[@]}" -o "$tmp/$name.wasm" "$tmp/.o/web.o" "${rt_objs[@]}" "${bake_objs[@]}"
if [ -f "$bake/$name.mcs" ]; then
    # the model comes through the stream, so none of the bake's objects: the module is the runtime
    # and its buffers, and the first picture needs only the stream's first levels
    "${wasm_cc[@]}" "${ldflags[@]}" -o "$tmp/$name-stream.wasm" "$tmp/.o/web-stream.o" "${rt_objs[@]}"
    cp "$bake/$name.mcs" "$tmp/$name.mcs"
    sed -e "s|<body data-model=\"@NAME@\">|<body data-model=\"@NAME@\" data-stream=\"@NAME@.mcs\">|" \
        -e "s|<title>@NAME@ |<title>@NAME@ (stream) |" -e "s|loading @NAME@.wasm|loading @NAME@-stream.wasm|" \
        -e "s/@NAME@/$name/g" -e "s/@WIDTH@/$w/g" -e "s/@HEIGHT@/$h/g" "$root/runtime/front/web/index.html" > "$tmp/stream.html"
    grep -q 'data-stream=' "$tmp/stream.html" || die "index.html: no <body data-model=\"@NAME@\"> to make stream.html of"
fi
rm -rf "$tmp/.o"
{ printf 'window.MODELC_WASM_BASE64 = "'; base64 -w0 "$tmp/$name.wasm"; printf '";\n'; } > "$tmp/$name.wasm.js"
cp "$root/runtime/front/web/viewer.js" "$tmp/viewer.js"
sed -e "s/@NAME@/$name/g" -e "s/@WIDTH@/$w/g" -e "s/@HEIGHT@/$h/g" "$root/runtime/front/web/index.html" > "$tmp/index.html"
chmod 755 "$tmp"
rm -rf "$out.old"
[ -e "$out" ] && mv "$out" "$out.old"
mv "$tmp" "$out"
rm -rf "$out.old"
trap - EXIT
echo "built $out/index.html ($name.wasm $(stat -c %s "$out/$name.wasm") bytes, canvas ${w}x${h})"
[ ! -f "$out/stream.html" ] ||
    echo "built $out/stream.html ($name-stream.wasm $(stat -c %s "$out/$name-stream.wasm") bytes, $name.mcs $(stat -c %s "$out/$name.mcs") bytes; serve $out over http)"
