# The suites' shared pieces. A suite cd's to the top of the checkout, sets TAP_PREFIX if it wants
# one, then sources this file, which brings in tests/tap.sh (ok, notok, skip, check_*, oneline).
# shellcheck shell=bash
. tests/tap.sh

# mkvar NAME [VAR=value...]: a Makefile variable as make computes it (so a test compiles or links
# exactly as the build does), with optional overrides such as BOARD=...
mkvar() { make -s --no-print-directory --eval 'mc-print-%: ; @echo $($*)' "mc-print-$1" "${@:2}"; }

# rt_objs [host]: the runtime's objects as the Makefile builds them for the viewers (CFLAGS and
# RT_CFLAGS, no hooks), made when out of date; with "host", the host front end's objects too. A test
# that checks the runtime as it ships links these instead of compiling runtime/src again (compiling
# it is most of several suites' time); a test that needs other flags or a hook compiles its own.
rt_objs() {
    make -s runtime-objs >/dev/null 2>&1 || { echo "rt_objs: make runtime-objs failed" >&2; return 1; }
    mkvar RT_OBJ
    [ "${1:-}" != host ] || mkvar HOST_OBJ
}

# runtime_snapshot DIR [REV]: runtime/include, src, front/host and front/common copied under
# DIR/runtime, from git revision REV when one is given, else from the working tree, so that every
# binary of a benchmark run is built from the same sources; prints where they came from
runtime_snapshot() {
    local dir=$1 rev=${2:-}
    rm -rf "$dir"
    mkdir -p "$dir/runtime/front"
    if [ -n "$rev" ]; then
        git archive "$rev" runtime/include runtime/src runtime/front/host runtime/front/common | tar -x -C "$dir" ||
            return 1
        echo "git revision $rev ($(git rev-parse --short "$rev"))"
    else
        cp -r runtime/include runtime/src "$dir/runtime/" && cp -r runtime/front/host runtime/front/common "$dir/runtime/front/" ||
            return 1
        echo "the working tree"
    fi
}

# ASan + UBSan, halting at the first report: the flags every sanitized test build uses, and the
# runtime options that make a report end the program. -g1: line tables only, so reports still name
# file and line, at two thirds of -g's compile time (sanitized compiles are much of make test).
SAN_FLAGS="-O1 -g1 -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
export ASAN_OPTIONS="${ASAN_OPTIONS:-abort_on_error=1:halt_on_error=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}"
sanitizer_report() {   # FILE: the first line of a sanitizer report in it, if any
    grep -m1 -E 'runtime error:|ERROR: AddressSanitizer|ERROR: LeakSanitizer|SUMMARY: (Address|Undefined|Leak)' "$1" | oneline
}

# fresh_dir DIR: DIR emptied (a suite's own output under build/, so a stale file never passes)
fresh_dir() { rm -rf "$1" && mkdir -p "$1"; }

# temp_dir: sets $tmp to a new temporary directory removed when the suite exits
temp_dir() {
    tmp=$(mktemp -d "${TMPDIR:-/tmp}/modelc-test.XXXXXX") || exit 1
    trap 'rm -rf "$tmp"' EXIT
}

# model_file NAME: the path of catalogue model NAME's source file under build/models/, extracted
# (make models) when missing; prints nothing and fails when it cannot be had
model_file() {
    local f src
    src=$(mkvar "$1.src")
    [ -n "$src" ] || return 1   # not a catalogue model
    f=build/models/$(basename "$src")
    [ -f "$f" ] || make -s "$f" >/dev/null 2>&1 || return 1
    echo "$f"
}

# cc_obj SRC CC FLAGS...: SRC compiled (-c) with that compiler and those flags, through the tests'
# shared object cache (tests/cc_cached.sh, which says how it is keyed); prints the object's path, or
# fails with the compiler's messages on stderr.
cc_obj() {
    local src=$1
    shift
    tests/cc_cached.sh --print "$@" "$src"
}

# model_dump_tool: the path of tests/gen/model_dump.cpp's program (what a reader makes of a file,
# exactly), linked with the generator's own reader objects (build/gen/input/*.o, made by make as
# make gen makes them: the readers modelc has, not compiled again for each suite), built into
# build/tests/model_dump when missing or older than its inputs; fails with the compiler's messages
# on stderr. gen/gltf.sh and gen/readers.sh share it.
model_dump_tool() {
    local tool=build/tests/model_dump objs
    objs=$(mkvar GEN_OBJ | tr ' ' '\n' | grep '^build/gen/input/' | tr '\n' ' ')
    [ -n "$objs" ] || { echo "model_dump_tool: no build/gen/input objects in GEN_OBJ" >&2; return 1; }
    # shellcheck disable=SC2086
    make -s $objs >&2 || return 1
    mkdir -p build/tests
    # shellcheck disable=SC2086
    if [ ! -x "$tool" ] || [ -n "$(find tests/gen/model_dump.cpp gen/*.hpp gen/input/*.hpp $objs -newer "$tool" 2>/dev/null | head -n 1)" ]; then
        # shellcheck disable=SC2046
        g++ -std=c++17 -O1 $(mkvar GEN_CXXFLAGS) -o "$tool.$BASHPID.tmp" tests/gen/model_dump.cpp $objs $(mkvar GEN_LIBS) &&
            mv "$tool.$BASHPID.tmp" "$tool" || { rm -f "$tool.$BASHPID.tmp"; return 1; }
    fi
    echo "$tool"
}
