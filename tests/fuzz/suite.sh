#!/usr/bin/env bash
# Replays every fuzzer finding (tests/fuzz/regress/TARGET/*, written by make fuzz; not track_input's,
# the tracker's input files, which tests/unit/test_track_input.c replays) and every absurd
# header (tests/fuzz/absurd/*: tiny files whose counts are just under the readers' limits, where a
# reader that allocates what the header says would take gigabytes) through the generator as a user
# would run it, with the bake fuzzer's options (--depth 5, --views front:40 for NAME.views.EXT, --as
# both for NAME.mesh.EXT).
# Each must end in exit status 0 (with its output written and nothing on stderr) or 1 (exactly one
# stderr line "modelc: ...", not "out of memory", no output left), never a signal, a sanitizer
# report or a hang (FUZZ_REPLAY_TIMEOUT, 20 s), within FUZZ_REPLAY_MEM_MB (256; a small bake needs
# under 128) of address space for the normal build, or of one allocation for a sanitized one
# (tests/sanitize/suite.sh replays them with build/san/bin/modelc).
#
# usage: tests/fuzz/suite.sh [MODELC]        (default build/bin/modelc)
set -u
MODELC=${1:-build/bin/modelc}
case $MODELC in /*) ;; *) MODELC=$PWD/$MODELC ;; esac
cd "$(dirname "$0")/../.." || exit 1
TAP_PREFIX="fuzz: "
. tests/lib.sh
temp_dir
TIMEOUT=${FUZZ_REPLAY_TIMEOUT:-20}
MEM_MB=${FUZZ_REPLAY_MEM_MB:-256}
[ -x "$MODELC" ] || { notok "setup" "$MODELC is not an executable (make gen)"; exit 1; }
# a sanitized build reserves terabytes of address space for its shadow memory: bound one
# allocation instead (an over-large one is then a report, so a failure)
sanitized=0
nm "$MODELC" 2>/dev/null | grep -q '__asan_init' && sanitized=1
export ASAN_OPTIONS="$ASAN_OPTIONS:max_allocation_size_mb=$MEM_MB:allocator_may_return_null=0"

# why the run of FILE is wrong, or nothing
judge() {
    local rc=$1 out=$2 lines
    if [ "$rc" -eq 124 ]; then echo "hangs (over $TIMEOUT s)"; return; fi
    if [ "$rc" -ge 128 ]; then echo "killed by signal $((rc - 128)): $(head -c 300 "$tmp/stderr" | oneline)"; return; fi
    rep=$(sanitizer_report "$tmp/stderr")
    if [ -n "$rep" ]; then echo "sanitizer report: $rep"; return; fi
    if [ "$rc" -eq 0 ]; then
        [ -s "$tmp/stderr" ] && { echo "exit status 0 but stderr: $(head -c 300 "$tmp/stderr" | oneline)"; return; }
        [ -f "$out/m/budget.json" ] || echo "exit status 0 but no $out/m/budget.json"
        return
    fi
    if [ "$rc" -ne 1 ]; then echo "exit status $rc, expected 0 or 1: $(head -c 300 "$tmp/stderr" | oneline)"; return; fi
    lines=$(awk 'END { print NR }' "$tmp/stderr")
    if [ "$lines" -ne 1 ]; then echo "stderr has $lines lines, expected 1: $(head -c 300 "$tmp/stderr" | oneline)"; return; fi
    case $(cat "$tmp/stderr") in
        "modelc: "*"out of memory"*) echo "$(cat "$tmp/stderr") (a tiny file must be refused, not exhaust memory)"; return ;;
        "modelc: "*) ;;
        *) echo "stderr does not start with 'modelc: ': $(head -c 300 "$tmp/stderr" | oneline)"; return ;;
    esac
    if [ -n "$(ls -A "$out")" ]; then echo "output left: $(ls -A "$out" | head -3 | oneline)"; fi
}

n=0
for f in tests/fuzz/regress/*/* tests/fuzz/absurd/*; do
    [ -f "$f" ] || continue
    case $f in tests/fuzz/regress/track_input/* | tests/fuzz/regress/stream/*) continue ;; esac   # not models: tests/unit/test_track_input.c
    n=$((n + 1))
    out=$tmp/out/$n
    mkdir -p "$out"
    args=(--name m --depth 5 -q)
    case $(basename "$f") in *.views.*) args+=(--views front:40) ;; esac
    case $(basename "$f") in *.mesh.*) args+=(--as both) ;; esac
    rc=0
    if [ "$sanitized" = 1 ]; then
        timeout "$TIMEOUT" "$MODELC" "$f" -o "$out" "${args[@]}" >/dev/null 2>"$tmp/stderr" || rc=$?
    else
        (ulimit -v $((MEM_MB * 1024)) && exec timeout "$TIMEOUT" "$MODELC" "$f" -o "$out" "${args[@]}") \
            >/dev/null 2>"$tmp/stderr" || rc=$?
    fi
    check_problems "${f#tests/fuzz/}: exit 0 or 1 with one 'modelc:' line, no signal, hang or output left" \
        "$(judge "$rc" "$out")"
done
[ "$n" -gt 0 ] || notok "regression files" "none under tests/fuzz/regress/ or tests/fuzz/absurd/"
exit $status
