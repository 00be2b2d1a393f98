#!/usr/bin/env bash
# cc_cached.sh CC ARGS...: runs "CC ARGS..." through the tests' shared object cache
# (build/tests/objcache/, as tests/lib.sh cc_obj): a compile of one source (-c -o OUT SRC) whose
# preprocessed text and other flags (everything but -D, -U, -I, -include, -isystem) equal an earlier
# compile's takes that compile's object and the .su and .ci files -fstack-usage and
# -fcallgraph-info write beside it (they name the source, not the object, so they are the same
# bytes); anything else runs as given. The firmware suites pass it as the Makefile's ARM_CC
# (make firmware ARM_CC="tests/fw/cc_cached.sh arm-none-eabi-gcc"): the runtime's objects are the
# same for a board's points, mesh and tracker firmware (MC_FW_MESH does not reach runtime/src),
# and are compiled once instead of once per firmware. Run from the top of the checkout.
set -u
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
# not one source compiled to one object: as given
if [ "$compile" != 1 ] || [ -z "$out" ] || [ -z "$src" ] || [ "${src#several}" != "$src" ] || [ ! -f "$src" ]; then
    exec "$cc" "$@"
fi
dir=build/tests/objcache
mkdir -p "$dir"
real=$(readlink -f "$(command -v "$cc")" 2>/dev/null || echo "$cc")
key=$({ echo "$real ${nonpp[*]} | $src"; "$cc" "${args[@]}" -E 2>/dev/null || echo "preprocessing failed $$ $RANDOM"; } |
    md5sum | cut -c1-24)
base=$dir/$(basename "${src%.*}")-$key
if [ ! -f "$base.o" ]; then
    tmpd=$(mktemp -d "$dir/tmp.XXXXXX") || exit 1
    "$cc" "${args[@]}" -c -o "$tmpd/o.o" || { st=$?; rm -rf "$tmpd"; exit $st; }
    for x in su ci; do [ -f "$tmpd/o.$x" ] && mv "$tmpd/o.$x" "$base.$x"; done
    mv "$tmpd/o.o" "$base.o"
    rm -rf "$tmpd"
else
    touch "$base.o"
fi
cp "$base.o" "$out"
for x in su ci; do [ -f "$base.$x" ] && cp "$base.$x" "${out%.o}.$x"; done
exit 0
