#!/usr/bin/env bash
# Streamed bakes (modelc --emit stream, runtime/src/stream.c, stream_mesh.c, stream_packed.c): bunny00
# at depth 8 (cones, 218 colours), kitten at depth 6 with one palette entry (a point set: no cones, no
# colours), and bunny00 --as both (version 2: the progressive mesh too, 6,000 faces; every mesh prefix
# draws its level as the bake's --lod, shaded, and lines once the adjacency is in), and the same with
# --stream-splits packed (version 3); the mesh arrays a whole stream fills, and the face bits its reader
# works out, equal the bake's byte for byte. budget.json's
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

for spec in "bunny00 $(model_file bunny00) --depth 8" "kitten $(model_file kitten) --depth 6 --palette 1" \
    "bunnymesh $(model_file bunny00) --depth 6 --as both --max-faces 6000" \
    "bunnypacked $(model_file bunny00) --depth 6 --as both --max-faces 6000 --stream-splits packed"; do
    read -r name model args <<<"$spec"
    # shellcheck disable=SC2086
    bake "$name" "$model" $args || continue
    mcs=$dir/$name/$name.mcs
    # shellcheck disable=SC2086
    if ! cc $SAN -o "$dir/check-$name" tests/stream/stream_check.c runtime/front/common/mesh_frame.c "$dir/$name"/*.c "${rt[@]}" 2>"$dir/cc-$name.log"; then
        notok "$name: stream_check builds" "$(oneline <"$dir/cc-$name.log")"
        continue
    fi
    first=$("$dir/check-$name" first "$mcs")
    problems=$(python3 - "$dir/$name/budget.json" "$mcs" "$first" <<'EOF'
import json, os, sys
b = json.load(open(sys.argv[1]))['stream']
f = sys.argv[3].split()
ends = {f[i]: int(f[i + 1]) for i in range(2, len(f), 3)}
depths = [ends[k] for k in ends if k.startswith('depth')]
p = []
size = os.path.getsize(sys.argv[2])
if b['bytes'] != size: p.append('bytes %d, file %d' % (b['bytes'], size))
if b['drawable_at'] != depths: p.append('drawable_at %s, the records end at %s' % (b['drawable_at'], depths))
bud = json.load(open(sys.argv[1]))
if 'pmesh' in bud:   # the buffer: the stream, then the mesh arrays (stream.h MC_STREAM_MESH_BYTES)
    m = bud['pmesh']
    V, V0, F, ib = m['vertices'], m['base_vertices'], m['faces'], m['index_bytes']
    want = (size + 3) // 4 * 4 + 6 * V + ib * V + ib * (V - V0) + 3 * ib * F + F + (V - V0 + 7) // 8   # face bits, split faces
    if open(sys.argv[2], 'rb').read(6)[4] == 3:   # packed splits: the decoder's state (MC_STREAM_PACKED_BYTES)
        want += 24 * F + 12 * V + 4
    first = [k for k in ends if k.startswith('mesh')]
    if b['buffer'] != want: p.append('buffer %d, the stream and its mesh arrays need %d' % (b['buffer'], want))
    if not first or b['mesh_levels'][0] != {'at': ends[first[0]], 'level': V0} or b['mesh_levels'][-1]['level'] != V:
        p.append('mesh_levels %s..%s, the base record ends at %s' % (b['mesh_levels'][0], b['mesh_levels'][-1], first and ends[first[0]]))
    if b['mesh_lines_at'] != ends.get('lines'): p.append('mesh_lines_at %s, the adjacency ends at %s' % (b['mesh_lines_at'], ends.get('lines')))
elif b['buffer'] != size: p.append('buffer %d for a stream of %d bytes' % (b['buffer'], size))
print('; '.join(p))
EOF
)
    check_problems "$name: budget.json's stream bytes, buffer and drawable_at (and mesh_levels, mesh_lines_at) are the file's size, what the reader needs and its records' ends" "$problems"
    read -r share deep < <(echo "$first" | python3 -c '
import sys
f = [w for w in sys.stdin.read().split()]
f = f[:f.index([w for w in f if w.startswith("mesh")][0])] if any(w.startswith("mesh") for w in f) else f
d = (len(f) - 2) // 3
print(f[4], "depth %d after %s of the bytes" % (d - 2, f[3 * (d - 2) + 1]) if d >= 3 else "")')
    python3 -c "import sys; sys.exit(0 if float('${share%\%}') <= 10 else 1)" &&
        ok "$name: the first picture (depth 1) after $share of the stream's bytes (at most 10 %); $deep" ||
        notok "$name: the first picture after at most 10 % of the bytes" "$first"
    case $name in *mesh | *packed)
        read -r mshare lshare < <(echo "$first" | python3 -c '
import sys
f = sys.stdin.read().split()
m = [i for i, w in enumerate(f) if w.startswith("mesh")][0]
print(f[m + 2], f[m + 5])')
        python3 -c "import sys; sys.exit(0 if float('${mshare%\%}') <= 10 else 1)" &&
            ok "$name: the mesh's first picture (its base) after $mshare of the stream's bytes (at most 10 %); its line styles after $lshare" ||
            notok "$name: the mesh's first picture after at most 10 % of the bytes" "$first"
        ;;
    esac
    runs="prefixes 60|corrupt 2000|forged 500"
    [ "$name" = kitten ] && runs="prefixes 100|corrupt 10000|forged 1000"
    [ "$name" = bunnymesh ] && runs="arrays 0|mesh 40|prefixes 20|corrupt 2000|forged 500"
    [ "$name" = bunnypacked ] && runs="arrays 0|mesh 40|corrupt 500|forged 800"   # its octree part is bunnymesh's
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

# packed splits need a stream with a mesh part
for args in "--as both --stream-splits packed" "--emit stream --stream-splits packed"; do
    rm -rf "$dir/nosplits"
    # shellcheck disable=SC2086
    if "$MODELC" "$(model_file bunny00)" -o "$dir" --name nosplits --depth 3 $args -q >"$dir/nosplits.log" 2>&1; then
        notok "$args is refused" "exit 0"
    else
        [ "$(wc -l <"$dir/nosplits.log")" = 1 ] && grep -q '^modelc: --stream-splits' "$dir/nosplits.log" && [ ! -e "$dir/nosplits" ] &&
            ok "$args: one modelc: line, no output" || notok "$args: one modelc: line, no output" "$(oneline <"$dir/nosplits.log")"
    fi
done

# the stream fuzzer's findings (make fuzz FUZZ_TARGETS=stream), replayed under the sanitizers
# shellcheck disable=SC2086
if cc $SAN -DMC_FUZZ_STREAM_MAIN -o "$dir/replay" tests/fuzz/fuzz_stream.c runtime/front/common/mesh_frame.c "${rt[@]}" 2>"$dir/cc-replay.log"; then
    files=(tests/fuzz/regress/stream/*)
    [ -e "${files[0]}" ] || files=()
    { printf '\0'; cat "$dir/bunny00/bunny00.mcs"; } >"$dir/whole.in"
    { printf '\0'; cat "$dir/bunnymesh/bunnymesh.mcs"; } >"$dir/whole-mesh.in"
    { printf '\0'; cat "$dir/bunnypacked/bunnypacked.mcs"; } >"$dir/whole-packed.in"
    if out=$("$dir/replay" "${files[@]}" "$dir/whole.in" "$dir/whole-mesh.in" "$dir/whole-packed.in" 2>&1); then
        ok "the fuzz target's check replays ${#files[@]} finding(s) and three whole streams (points; points and mesh; mesh splits packed) without a fault"
    else
        notok "fuzz findings replayed" "$(echo "$out" | head -c 300 | oneline)"
    fi
else
    notok "the fuzz target builds for replay" "$(oneline <"$dir/cc-replay.log")"
fi
exit $status
