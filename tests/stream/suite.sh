#!/usr/bin/env bash
# Streamed bakes (modelc --emit stream, runtime/src/stream.c): bunny00 at depth 8 (cones, 218 colours)
# and kitten at depth 6 with one palette entry (a point set: no cones, no colours). budget.json's
# stream figures against the file; every prefix draws its deepest complete level exactly as the bake
# does; damaged streams (10^4 of kitten's, 2,000 of bunny00's) refused without a fault; forged streams (valid CRCs) refused by the
# reader's checks or drawn without a fault; the first picture's share of the bytes; the fuzzer's
# findings replayed. Everything under ASan + UBSan.
set -u
cd "$(dirname "$0")/../.."
TAP_PREFIX="stream: "
. tests/lib.sh

dir=build/tests/stream
rm -rf "$dir" && mkdir -p "$dir"
MODELC=build/bin/modelc
[ -x "$MODELC" ] || { notok "generator built"; exit 1; }
SAN="-std=c99 $SAN_FLAGS -Wall -Wextra -Werror -Iruntime/include"

# the runtime once for every program here; the renderer's leaves in their loop form (MC_LEAF_SWITCH=0:
# the same per-leaf code; the switch compiles some 30 times slower under the sanitizers, and
# make stress checks it under them)
mkdir -p "$dir/rt"
rt=()
for f in runtime/src/*.c; do
    o=$dir/rt/$(basename "$f" .c).o
    # shellcheck disable=SC2086
    cc $SAN -DMC_LEAF_SWITCH=0 -c -o "$o" "$f" 2>>"$dir/rt.log" || { notok "the runtime builds under the sanitizers" "$(oneline <"$dir/rt.log")"; exit 1; }
    rt+=("$o")
done

bake() {   # NAME MODEL ARGS...
    local name=$1 model=$2
    shift 2
    if "$MODELC" "$model" -o "$dir" --name "$name" --emit stream -q "$@" >"$dir/$name.log" 2>&1; then
        ok "$name: modelc --emit stream $* writes $name.mcs beside the C sources"
    else
        notok "$name: modelc --emit stream $*" "$(oneline <"$dir/$name.log")"
        return 1
    fi
}

for spec in "bunny00 $(model_file bunny00) --depth 8" "kitten $(model_file kitten) --depth 6 --palette 1"; do
    read -r name model args <<<"$spec"
    # shellcheck disable=SC2086
    bake "$name" "$model" $args || continue
    mcs=$dir/$name/$name.mcs
    # shellcheck disable=SC2086
    if ! cc $SAN -o "$dir/check-$name" tests/stream/stream_check.c "$dir/$name"/*.c "${rt[@]}" 2>"$dir/cc-$name.log"; then
        notok "$name: stream_check builds" "$(oneline <"$dir/cc-$name.log")"
        continue
    fi
    first=$("$dir/check-$name" first "$mcs")
    problems=$(python3 - "$dir/$name/budget.json" "$mcs" "$first" <<'EOF'
import json, os, sys
b = json.load(open(sys.argv[1]))['stream']
f = sys.argv[3].split()
ends = [int(f[i + 1]) for i in range(2, len(f), 3)]
p = []
if b['bytes'] != os.path.getsize(sys.argv[2]): p.append('bytes %d, file %d' % (b['bytes'], os.path.getsize(sys.argv[2])))
if b['drawable_at'] != ends: p.append('drawable_at %s, the records end at %s' % (b['drawable_at'], ends))
print('; '.join(p))
EOF
)
    check_problems "$name: budget.json's stream bytes and drawable_at are the file's size and its level records' ends" "$problems"
    read -r share deep < <(echo "$first" | python3 -c '
import sys
f = sys.stdin.read().split()
d = (len(f) - 2) // 3
print(f[4], "depth %d after %s of the bytes" % (d - 2, f[3 * (d - 2) + 1]) if d >= 3 else "")')
    python3 -c "import sys; sys.exit(0 if float('${share%\%}') <= 10 else 1)" &&
        ok "$name: the first picture (depth 1) after $share of the stream's bytes (at most 10 %); $deep" ||
        notok "$name: the first picture after at most 10 % of the bytes" "$first"
    runs="prefixes 60|corrupt 2000|forged 500"
    [ "$name" = bunny00 ] || runs="prefixes 100|corrupt 10000|forged 1000"
    IFS='|' read -r -a modes <<<"$runs"
    for mode in "${modes[@]}"; do
        read -r m n <<<"$mode"
        out=$("$dir/check-$name" "$m" "$mcs" "$n" 7 2>&1)
        if [ $? -eq 0 ] && [[ $out == ok* ]]; then ok "$name: $(echo "$out" | cut -c4-)"; else notok "$name: $m" "$(echo "$out" | head -c 400 | oneline)"; fi
    done
done

# the bake refuses what has no octree
if "$MODELC" /usr/share/visp-images-data/ViSP-images/mbt/cube.cao -o "$dir" --name cubes --as edges --emit stream -q >"$dir/edges.log" 2>&1; then
    notok "--as edges --emit stream is refused" "exit 0"
else
    [ "$(wc -l <"$dir/edges.log")" = 1 ] && grep -q '^modelc: ' "$dir/edges.log" && [ ! -e "$dir/cubes" ] &&
        ok "--as edges --emit stream: one modelc: line, no output" || notok "--as edges --emit stream: one modelc: line, no output" "$(oneline <"$dir/edges.log")"
fi

# the stream fuzzer's findings (make fuzz FUZZ_TARGETS=stream), replayed under the sanitizers
# shellcheck disable=SC2086
if cc $SAN -DMC_FUZZ_STREAM_MAIN -o "$dir/replay" tests/fuzz/fuzz_stream.c "${rt[@]}" 2>"$dir/cc-replay.log"; then
    files=(tests/fuzz/regress/stream/*)
    [ -e "${files[0]}" ] || files=()
    { printf '\0'; cat "$dir/bunny00/bunny00.mcs"; } >"$dir/whole.in"
    if out=$("$dir/replay" "${files[@]}" "$dir/whole.in" 2>&1); then
        ok "the fuzz target's check replays ${#files[@]} finding(s) and a whole stream without a fault"
    else
        notok "fuzz findings replayed" "$(echo "$out" | head -c 300 | oneline)"
    fi
else
    notok "the fuzz target builds for replay" "$(oneline <"$dir/cc-replay.log")"
fi
exit $status
