#!/usr/bin/env bash
# Builds the web viewer of a bake: build.sh BUILD NAME [WxH]
#   BUILD/NAME/ holds the bake (modelc -o BUILD --name NAME); writes BUILD/NAME/web/:
#   NAME.wasm     the runtime, the bake and web.c; clang --target=wasm32 -nostdlib, wasm-ld; no imports
#   NAME.wasm.js  the same bytes in base64, for pages opened from file:// (which cannot fetch)
#   viewer.js     the page's script; index.html the page, its canvas WxH (default: the bake's screen
#                 up to 640x480)
# The folder is replaced whole or not at all: everything is written beside it and renamed at the end.
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 BUILD NAME [WxH]" >&2; exit 2; }
build=$1 name=$2 size=${3:-}
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
bake=$build/$name
header=$bake/$name.h
die() { echo "modelc web: $*" >&2; exit 1; }
[ -f "$header" ] || die "$header: no bake named $name under $build (run modelc -o $build --name $name first)"
command -v "${WASM_CC:-clang}" >/dev/null || die "${WASM_CC:-clang} not found (make deps installs clang and lld)"
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
# -nostdlib: no libc and no compiler runtime; the runtime needs neither (freestanding, no heap)
"${WASM_CC:-clang}" --target=wasm32 -nostdlib -O2 -std=c99 -ffreestanding -Wall -Wextra -Werror \
    -I"$root/runtime/include" -DMC_WEB_MAX_PIXELS="($sw * $sh)" \
    -Wl,--no-entry -Wl,--gc-sections -Wl,--strip-all \
    -o "$tmp/$name.wasm" "$root/runtime/front/web/web.c" "$root/runtime/front/common/rgb.c" \
    "$root"/runtime/src/*.c "$bake"/*.c
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
