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
[ -d "$dir" ] || mkdir -p "$dir"
# (a hit runs the preprocessor and md5sum, and copies or prints: no other program, as most calls hit)
real=$(type -P -- "$cc") || real=$cc
[ -L "$real" ] && real=$(readlink -f "$real")
key=$({ echo "$real ${nonpp[*]} | $src"; "$cc" "${args[@]}" -E 2>/dev/null || echo "preprocessing failed $$ $RANDOM"; } | md5sum)
name=${src##*/}
base=$dir/${name%.*}-${key:0:24}
# what the compile writes: the object, and with -fstack-usage and -fcallgraph-info its .su and .ci
files=("$base.o")
[[ " ${nonpp[*]} " == *" -fstack-usage "* ]] && files+=("$base.su")
[[ " ${nonpp[*]} " == *" -fcallgraph-info"* ]] && files+=("$base.ci")
hit=1
for f in "${files[@]}"; do [ -f "$f" ] || hit=0; done
if [ "$hit" = 0 ]; then
    # $dir/.day: a day older than the last miss (an object touched since is newer); files unused for
    # a week are removed
    touch -d '1 day ago' "$dir/.day"
    find "$dir" -maxdepth 1 -type f ! -name .day -mtime +7 -delete 2>/dev/null
    tmpd=$(mktemp -d "$dir/tmp.XXXXXX") || exit 1
    "$cc" "${args[@]}" -c -o "$tmpd/o.o" || { st=$?; rm -rf "$tmpd"; exit $st; }
    for x in su ci; do [ -f "$tmpd/o.$x" ] && mv "$tmpd/o.$x" "$base.$x"; done
    mv "$tmpd/o.o" "$base.o"
    rm -rf "$tmpd"
elif [ "$base.o" -ot "$dir/.day" ]; then
    touch "${files[@]}"   # in use: kept a week more (touched at most once a day)
fi
if [ "$print" = 1 ]; then echo "$base.o"; exit 0; fi
cp "$base.o" "$out"
# the .su and .ci beside it: small text files, copied without a program
for x in su ci; do
    if [ -f "$base.$x" ]; then IFS= read -r -d '' text <"$base.$x"; printf '%s' "$text" >"${out%.o}.$x"; fi
done
exit 0
