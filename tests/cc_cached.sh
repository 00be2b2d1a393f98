#!/usr/bin/env bash
# cc_cached.sh [--print] CC ARGS...: runs "CC ARGS..." through the tests' shared object cache,
# build/tests/objcache/. A compile of one source (-c [-o OUT] SRC) is keyed by the compiler's real
# path, the flags that are not preprocessor flags (everything but -D, -U, -I, -include, -isystem,
# -imacros, -iquote, -idirafter, in the order given) and the preprocessed source (CC -E): two
# compiles whose preprocessed text and code-generation flags are the same make the same code, so
# the second takes the first one's object, and the .su and .ci files -fstack-usage and
# -fcallgraph-info write beside it (they name the source, not the object: the same bytes). A
# runtime source that a test's macro (MC_FRAC_BITS, the plot hook, the leaf switch, MC_FW_MESH) does
# not reach is so compiled once for the whole test run, not once per program, form or firmware.
#   cc_cached.sh CC ARGS...          copies the object to OUT (the firmware suites pass it as the
#                                    Makefile's ARM_CC); anything but one source to one object runs
#                                    as given
#   cc_cached.sh --print CC ARGS...  prints the cached object's path instead (tests/lib.sh cc_obj)
# Objects are written to a temporary name and moved (two suites run at once); those unused for a
# week are removed. Fails with the compiler's messages on stderr. Run from the top of the checkout.
set -u
print=0
[ "${1:-}" = --print ] && { print=1; shift; }
cc=$1
shift
out="" src="" compile=0 skip=0 next_out=0
args=() nonpp=()
for a in "$@"; do
    if [ "$next_out" = 1 ]; then out=$a; next_out=0; continue; fi
    case $a in
        -o) next_out=1; continue ;;
        -c) compile=$((compile + 1)); continue ;;
    esac
    args+=("$a")
    if [ "$skip" = 1 ]; then skip=0; continue; fi
    case $a in
        -include | -isystem | -imacros | -iquote | -idirafter) skip=1 ;;
        -D* | -U* | -I*) ;;
        *.c | *.cc | *.cpp) src=${src:+several}$a ;;
        *) nonpp+=("$a") ;;
    esac
done
[ "$print" = 1 ] && compile=1 out=-
# not one source compiled to one object: as given
if [ "$compile" != 1 ] || [ -z "$out" ] || [ -z "$src" ] || [ "${src#several}" != "$src" ] || [ ! -f "$src" ]; then
    [ "$print" = 1 ] && { echo "cc_cached.sh --print: not one source: $*" >&2; exit 2; }
    exec "$cc" "$@"
fi
dir=build/tests/objcache
mkdir -p "$dir"
real=$(readlink -f "$(command -v "$cc")" 2>/dev/null || echo "$cc")
key=$({ echo "$real ${nonpp[*]} | $src"; "$cc" "${args[@]}" -E 2>/dev/null || echo "preprocessing failed $$ $RANDOM"; } |
    md5sum | cut -c1-24)
base=$dir/$(basename "${src%.*}")-$key
if [ ! -f "$base.o" ]; then
    find "$dir" -maxdepth 1 -type f -mtime +7 -delete 2>/dev/null
    tmpd=$(mktemp -d "$dir/tmp.XXXXXX") || exit 1
    "$cc" "${args[@]}" -c -o "$tmpd/o.o" || { st=$?; rm -rf "$tmpd"; exit $st; }
    for x in su ci; do [ -f "$tmpd/o.$x" ] && mv "$tmpd/o.$x" "$base.$x"; done
    mv "$tmpd/o.o" "$base.o"
    rm -rf "$tmpd"
else
    touch "$base.o"
fi
if [ "$print" = 1 ]; then echo "$base.o"; exit 0; fi
cp "$base.o" "$out"
for x in su ci; do [ -f "$base.$x" ] && cp "$base.$x" "${out%.o}.$x"; done
exit 0
