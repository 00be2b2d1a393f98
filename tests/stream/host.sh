#!/usr/bin/env bash
# The host viewer's --stream (runtime/front/host/stream_in.c) on bunny00 baked at depth 7 with
# --emit stream, against the same viewer drawing its compiled-in octree at --depth d: the whole
# stream from a pipe, a FIFO and a TCP socket on localhost (sent in pieces with pauses: a line per
# level as it becomes drawable); cuts at every level's end, a byte before it and at random: the
# frame of the deepest complete level, the truncation reported, exit status 1, and no file when
# nothing was drawable; a flipped byte and a wrong version: the error and its byte, the last good
# level drawn; --stream refused by a bake without a stream buffer. And a version-2 stream (bunny00
# --as both at depth 4): its mesh drawn shaded and in lines as the compiled-in mesh at the level
# that came (--lod), whole and cut after mesh records; a mesh larger than the viewer's buffers; and
# with --stream-splits packed (version 3), through a viewer whose buffer holds the decoder's state.
set -u
cd "$(dirname "$0")/../.."
TAP_PREFIX="stream: host: "
. tests/lib.sh

dir=build/tests/stream-host
fresh_dir "$dir"
model=$(model_file bunny00) || { notok "bunny00's model file (make models)"; exit 1; }
rt_objs >/dev/null || { notok "make runtime-objs"; exit 1; }
link() {   # NAME: the viewer of the bake in $dir/NAME, as the Makefile links it
    # shellcheck disable=SC2046
    gcc $(mkvar CFLAGS) $(mkvar RT_CFLAGS) -ffunction-sections -fdata-sections -o "$dir/$1/$1-view" "$dir/$1"/*.c \
        $(rt_objs host) $(mkvar VIEW_LDFLAGS) >"$dir/$1.link.log" 2>&1
}
if build/bin/modelc "$model" -o "$dir" --name bunny --depth 7 --emit stream -q >"$dir/bake.log" 2>&1 && link bunny &&
    build/bin/modelc "$model" -o "$dir" --name plain --depth 4 -q >>"$dir/bake.log" 2>&1 && link plain; then
    ok "bunny00 baked at depth 7 with --emit stream and at depth 4 without; their viewers link"
else
    notok "bakes and viewers" "$(cat "$dir/bake.log" "$dir"/*.link.log 2>/dev/null | tail -n 5 | oneline)"
    exit 1
fi
view=$dir/bunny/bunny-view
mcs=$dir/bunny/bunny.mcs
read -r -a ends < <(python3 -c "import json,sys; print(*json.load(open(sys.argv[1]))['stream']['drawable_at'])" "$dir/bunny/budget.json")
size=$(stat -c %s "$mcs")

# the native frames of every depth, from the compiled-in octree
for d in $(seq 1 ${#ends[@]}); do "$view" --depth "$d" --yaw 30 --pitch 20 --ppm "$dir/ref-$d.ppm" >/dev/null; done

# the whole stream from a pipe, a FIFO and a TCP socket
"$view" --stream - --yaw 30 --pitch 20 --ppm "$dir/pipe.ppm" <"$mcs" >"$dir/pipe.out" 2>&1
rc=$?
[ $rc -eq 0 ] && cmp -s "$dir/pipe.ppm" "$dir/ref-7.ppm" && grep -q "^stream: complete, depth 7, $size bytes" "$dir/pipe.out" &&
    ok "the whole stream on standard input: complete, the frame equals --depth 7's, exit 0" ||
    notok "the whole stream on standard input" "exit $rc; $(oneline <"$dir/pipe.out")"
mkfifo "$dir/fifo"
{ head -c 5000 "$mcs"; sleep 0.3; tail -c +5001 "$mcs"; } >"$dir/fifo" &
"$view" --stream "$dir/fifo" --yaw 30 --pitch 20 --ppm "$dir/fifo.ppm" >"$dir/fifo.out" 2>&1
rc=$?
wait
[ $rc -eq 0 ] && cmp -s "$dir/fifo.ppm" "$dir/ref-7.ppm" && grep -q '^stream: depth 7 of 7 after' "$dir/fifo.out" &&
    grep -q '^stream: depth [1-6] of 7 after [0-9]* of' "$dir/fifo.out" &&
    ok "the whole stream from a FIFO in two pieces with a pause: a level drawable from the first, the frame equals --depth 7's" ||
    notok "the whole stream from a FIFO" "exit $rc; $(oneline <"$dir/fifo.out")"
port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
python3 - "$port" "$mcs" "${ends[@]}" >"$dir/server.log" 2>&1 <<'EOF' &
import socket, sys, time
port, path, ends = int(sys.argv[1]), sys.argv[2], [int(e) for e in sys.argv[3:]]
data = open(path, 'rb').read()
s = socket.socket()
s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
s.bind(('127.0.0.1', port))
s.listen(1)
print('ready', flush=True)
s.settimeout(30)
c, _ = s.accept()
at = 0
for e in ends + [len(data)]:
    c.sendall(data[at:e])
    at = e
    time.sleep(0.1)
c.close()
EOF
server=$!
for _ in $(seq 50); do grep -q ready "$dir/server.log" && break; sleep 0.1; done
timeout 60 "$view" --stream "tcp:127.0.0.1:$port" --yaw 30 --pitch 20 --ppm "$dir/tcp.ppm" >"$dir/tcp.out" 2>&1
rc=$?
wait $server
levels=$(grep -c '^stream: depth [0-9]* of 7 after' "$dir/tcp.out")
[ $rc -eq 0 ] && cmp -s "$dir/tcp.ppm" "$dir/ref-7.ppm" && [ "$levels" -ge 5 ] &&
    ok "the whole stream over TCP on localhost, a level at a time with pauses: $levels lines as levels became drawable, the frame equals --depth 7's" ||
    notok "the whole stream over TCP" "exit $rc, $levels level lines; $(oneline <"$dir/tcp.out")"

# cuts: every level's end, a byte before it, inside the header, and at random (seeded)
cuts=(0 10 19 20 $((size - 1)))
for e in "${ends[@]}"; do cuts+=("$e" $((e - 1))); done
while read -r c; do cuts+=("$c"); done < <(python3 -c "import random; r = random.Random(11); print('\n'.join(str(r.randrange(1, $size)) for _ in range(10)))")
problems=""
for k in "${cuts[@]}"; do
    d=0
    for e in "${ends[@]}"; do [ "$k" -ge "$e" ] && d=$((d + 1)); done
    head -c "$k" "$mcs" >"$dir/cut.mcs"
    rm -f "$dir/cut.ppm"
    "$view" --stream "$dir/cut.mcs" --yaw 30 --pitch 20 --ppm "$dir/cut.ppm" >"$dir/cut.out" 2>"$dir/cut.err"
    rc=$?
    [ $rc -eq 1 ] || { problems+="cut $k: exit $rc; "; continue; }
    [ "$(wc -l <"$dir/cut.err")" = 1 ] && grep -q "^bunny-view: stream: truncated at byte $k; " "$dir/cut.err" ||
        problems+="cut $k: $(oneline <"$dir/cut.err"); "
    if [ "$d" -eq 0 ]; then
        [ ! -e "$dir/cut.ppm" ] && grep -q "nothing was drawable" "$dir/cut.err" || problems+="cut $k: nothing drawable, yet a frame or no word of it; "
    else
        cmp -s "$dir/cut.ppm" "$dir/ref-$d.ppm" || problems+="cut $k: not --depth $d's frame; "
        grep -q "drawing depth $d," "$dir/cut.err" || problems+="cut $k: not depth $d; "
    fi
done
check_problems "${#cuts[@]} cuts (the header, every level's end and a byte before it, 10 at random): one line 'truncated at byte k', exit 1, the frame of the deepest complete level, no file when nothing was drawable" "$problems"

# damage: a flipped byte in level 5's record, a wrong version (the header's CRC made valid)
python3 - "$mcs" "$dir" "${ends[@]}" <<'EOF'
import struct, sys, zlib
data = bytearray(open(sys.argv[1], 'rb').read())
ends = [int(e) for e in sys.argv[3:]]
flip = bytearray(data)
at = (ends[3] + ends[4]) // 2
flip[at] ^= 0x40
open(sys.argv[2] + '/flip.mcs', 'wb').write(flip)
open(sys.argv[2] + '/flip.at', 'w').write('%d %d\n' % (at, ends[3]))
ver = bytearray(data)
ver[4:6] = struct.pack('<H', 4)
ver[16:20] = struct.pack('<I', zlib.crc32(bytes(ver[:16])))
open(sys.argv[2] + '/version.mcs', 'wb').write(ver)
EOF
problems=""
"$view" --stream "$dir/flip.mcs" --yaw 30 --pitch 20 --ppm "$dir/flip.ppm" >/dev/null 2>"$dir/flip.err"
rc=$?
[ $rc -eq 1 ] && grep -q "^bunny-view: stream: crc at byte [0-9]*; drawing depth 4, the last complete level" "$dir/flip.err" &&
    cmp -s "$dir/flip.ppm" "$dir/ref-4.ppm" || problems+="flipped byte: exit $rc, $(oneline <"$dir/flip.err"); "
rm -f "$dir/version.ppm"
"$view" --stream - --ppm "$dir/version.ppm" <"$dir/version.mcs" >/dev/null 2>"$dir/version.err"
rc=$?
[ $rc -eq 1 ] && grep -q "^bunny-view: stream: version at byte 4; nothing was drawable" "$dir/version.err" && [ ! -e "$dir/version.ppm" ] ||
    problems+="version 4: exit $rc, $(oneline <"$dir/version.err"); "
check_problems "a flipped byte in level 5: 'crc at byte N', depth 4's frame kept; version 4: 'version at byte 4', no file; exit 1 both" "$problems"

# interactive FILE CUT STATUS FIRST REST VIEWER ARGS...: the viewer in a tmux pane reading a FIFO; FILE's
# first CUT bytes sent, the status line (the last line matching STATUS) must match FIRST within 20 s;
# then the rest sent, and it must match REST. Prints the problems, if any.
interactive() {
    local file=$1 cut=$2 status_re=$3 first=$4 rest=$5 sock=mcstream$$ fifo=$dir/ififo$$ problems=""
    shift 5
    tm() { tmux -u -L "$sock" -f /dev/null "$@"; }
    line() { tm capture-pane -p -t s 2>/dev/null | grep -E "$status_re" | tail -n 1; }
    wait_for() { for _ in $(seq 400); do line | grep -qE "$1" && return 0; sleep 0.05; done; return 1; }
    rm -f "$fifo" && mkfifo "$fifo"
    TERM=xterm-256color LC_ALL=C.UTF-8 tm new-session -d -s s -x 200 -y 40 "$* --stream $PWD/$fifo"
    exec 3>"$fifo"
    head -c "$cut" "$file" >&3
    wait_for "$first" || problems+="the first $cut bytes sent: '$(line)'; "
    tail -c +$((cut + 1)) "$file" >&3
    exec 3>&-
    wait_for "$rest" || problems+="the rest sent: '$(line)'; "
    tm send-keys -t s q
    for _ in $(seq 100); do tm has-session -t s 2>/dev/null || break; sleep 0.05; done
    tm kill-server 2>/dev/null
    echo "$problems"
}

# interactive, in a tmux pane: levels drawn as they arrive over a FIFO, then damage: the error in
# the status line and the last good level still on screen
if command -v tmux >/dev/null; then
    problems=$(interactive "$dir/flip.mcs" "${ends[2]}" ' depth [0-9]+/[0-9]+ ' \
        "depth 3/3 .*stream: depth 3 of 7 after ${ends[2]} of $size bytes" \
        "depth 4/4 .*stream: crc at byte [0-9]+; drawing depth 4, the last complete level" "$PWD/$view")
    check_problems "interactive (tmux): depth 3 on screen once levels 1-3 came through a FIFO; after the rest with a flipped byte in level 5, the crc error in the status line and depth 4 drawn" "$problems"
else
    notok "interactive --stream" "tmux missing (make deps installs it)"
fi

# the mesh part (--as both: a version-2 stream), against the same viewer's compiled-in mesh at --lod L:
# whole, cut after mesh records (shaded; lines drawn shaded until the adjacency), --lod below what came.
# That viewer's bake keeps a neighbour table (--mesh-neighbours, pmesh.h); the small bake's does not.
if build/bin/modelc "$model" -o "$dir" --name mesh --depth 4 --as both --emit stream --mesh-neighbours -q >"$dir/mesh-bake.log" 2>&1 && link mesh &&
    build/bin/modelc "$model" -o "$dir" --name small --depth 8 --as both --max-faces 2000 --emit stream -q >>"$dir/mesh-bake.log" 2>&1 &&
    link small && build/bin/modelc "$model" -o "$dir" --name other --depth 2 --as both --max-faces 6000 --emit stream -q >>"$dir/mesh-bake.log" 2>&1; then
    mview=$dir/mesh/mesh-view
    mmcs=$dir/mesh/mesh.mcs
    msize=$(stat -c %s "$mmcs")
    read -r full lines_at < <(python3 -c "import json,sys; b=json.load(open(sys.argv[1])); print(b['pmesh']['vertices'], b['stream']['mesh_lines_at'])" "$dir/mesh/budget.json")
    mapfile -t mlevels < <(python3 -c "import json,sys; [print(m['at'], m['level']) for m in json.load(open(sys.argv[1]))['stream']['mesh_levels']]" "$dir/mesh/budget.json")
    # the neighbour table: in the budget and the binding, kept by the viewer for its mesh and for a
    # streamed one once its adjacency has come, the same drawings as the small bake's viewer without one
    problems=$(python3 -c "
import json, sys
b = json.load(open(sys.argv[1])); pm = b['pmesh']
want = 3 * pm['faces'] * pm['half_edge_bytes']
print('' if pm['neighbour_ram'] == want == b['ram']['pmesh_neighbours'] and
      b['ram']['image'] == sum(v for k, v in b['ram'].items() if k not in ('image', 'total', 'note')) else
      f\"neighbour_ram {pm['neighbour_ram']}, ram.pmesh_neighbours {b['ram']['pmesh_neighbours']}, 3 F half-edges {want}\")
" "$dir/mesh/budget.json")
    grep -q "static uint8_t mc_mesh_pmesh_nbr\[MC_MESH_PMESH_NEIGHBOUR_BYTES\]" "$dir/mesh/mesh_app.c" || problems+=" mesh_app.c declares no table;"
    grep -q "neighbour-table" <("$mview" --mode lines --lod 500 --bench 2 2>&1) || problems+=" mesh-view --bench keeps no table;"
    grep -q "neighbour-table" <("$dir/small/small-view" --mode lines --lod 500 --bench 2 2>&1) && problems+=" small-view (baked without) keeps one;"
    for l in 300 1000; do
        "$mview" --stream "$dir/small/small.mcs" --mode lines --lod $l --yaw 30 --pitch 20 --ppm "$dir/nbr-$l.ppm" >/dev/null 2>&1
        "$dir/small/small-view" --mode lines --lod $l --yaw 30 --pitch 20 --ppm "$dir/nonbr-$l.ppm" >/dev/null 2>&1
        cmp -s "$dir/nbr-$l.ppm" "$dir/nonbr-$l.ppm" || problems+=" lines at --lod $l differ;"
    done
    cmp -s <("$mview" --stream "$dir/small/small.mcs" --checksums | grep '^mesh') <("$dir/small/small-view" --checksums | grep '^mesh') ||
        problems+=" --checksums' mesh frames differ;"
    check_problems "--mesh-neighbours: budget.json's neighbour_ram 3 F half-edges, in the app binding; the viewer keeps the table (--bench says so; not the small bake's); the small bake's stream drawn with it in lines at --lod 300 and 1000 and in --checksums' mesh frames as the small viewer draws them without" "$problems"
    problems=""
    for m in shaded lines; do
        "$mview" --mode $m --yaw 30 --pitch 20 --ppm "$dir/mref-$m.ppm" >/dev/null
        "$mview" --stream - --mode $m --yaw 30 --pitch 20 --ppm "$dir/mwhole-$m.ppm" <"$mmcs" >"$dir/mwhole.out" 2>&1
        rc=$?
        [ $rc -eq 0 ] && cmp -s "$dir/mwhole-$m.ppm" "$dir/mref-$m.ppm" && grep -q "^stream: mesh level $full of $full after" "$dir/mwhole.out" &&
            grep -q "^stream: mesh lines after $msize of $msize bytes" "$dir/mwhole.out" || problems+="whole, $m: exit $rc, $(oneline <"$dir/mwhole.out"); "
    done
    check_problems "mesh: the whole version-2 stream on standard input, --mode shaded and lines: a line for the mesh's level and its lines, frames equal the compiled-in mesh's" "$problems"
    problems=""
    n=${#mlevels[@]}
    for i in 0 1 $((n / 2)) $((n - 2)); do
        read -r at level <<<"${mlevels[$i]}"
        head -c "$at" "$mmcs" >"$dir/mcut.mcs"
        "$mview" --mode shaded --lod "$level" --yaw 30 --pitch 20 --ppm "$dir/mref.ppm" >/dev/null
        for m in shaded lines; do
            "$mview" --stream "$dir/mcut.mcs" --mode $m --yaw 30 --pitch 20 --ppm "$dir/mcut.ppm" >"$dir/mcut.out" 2>"$dir/mcut.err"
            rc=$?
            [ $rc -eq 1 ] && cmp -s "$dir/mcut.ppm" "$dir/mref.ppm" && grep -q "truncated at byte $at; .*mesh level $level$" "$dir/mcut.err" &&
                { [ $m = shaded ] || grep -q "drawing shaded: the line styles need the mesh's adjacency" "$dir/mcut.err"; } ||
                problems+="cut $at ($m): exit $rc, $(oneline <"$dir/mcut.err"); "
        done
    done
    read -r at level <<<"${mlevels[$((n / 2))]}"
    low=$((level / 2))
    head -c $((at + 7)) "$mmcs" >"$dir/mcut.mcs"
    "$mview" --mode shaded --lod "$low" --yaw 30 --pitch 20 --ppm "$dir/mref.ppm" >/dev/null
    "$mview" --stream "$dir/mcut.mcs" --mode shaded --lod "$low" --yaw 30 --pitch 20 --ppm "$dir/mcut.ppm" >/dev/null 2>&1
    cmp -s "$dir/mcut.ppm" "$dir/mref.ppm" || problems+="--lod $low of $level come: not --lod $low's frame; "
    head -c $((lines_at - 1)) "$mmcs" >"$dir/mcut.mcs"
    "$mview" --stream "$dir/mcut.mcs" --mode lines --yaw 30 --pitch 20 --ppm "$dir/mcut.ppm" >/dev/null 2>"$dir/mcut.err"
    "$mview" --mode shaded --yaw 30 --pitch 20 --ppm "$dir/mref.ppm" >/dev/null
    cmp -s "$dir/mcut.ppm" "$dir/mref.ppm" && grep -q "mesh level $full$" "$dir/mcut.err" || problems+="a byte short of the adjacency: $(oneline <"$dir/mcut.err"); "
    check_problems "mesh: cut after the base, a batch of splits, the middle one and the last: exit 1, 'truncated at byte k', the frame of the compiled-in mesh at that level (--lod), shaded and (lines) drawn shaded with a note; --lod below what came; a byte short of the adjacency: the full level, shaded" "$problems"
    if command -v tmux >/dev/null; then   # interactive: the mesh drawn as its levels come
        read -r at level <<<"${mlevels[$((n / 2))]}"
        problems=$(interactive "$mmcs" "$at" ' shaded \| [0-9]+/[0-9]+ vertices ' \
            " shaded \| $level/$full vertices .*mesh $level of $full vertices \(no lines yet\)" \
            " shaded \| $full/$full vertices .*stream: complete" "$PWD/$mview" --mode shaded)
        check_problems "mesh, interactive (tmux, --mode shaded): level $level of $full on screen once the stream came up to its batch, then the full level when the rest came" "$problems"
    else
        notok "interactive --stream --mode shaded" "tmux missing (make deps installs it)"
    fi
    problems=""
    rm -f "$dir/refused.ppm"
    "$mview" --stream "$mcs" --mode shaded --ppm "$dir/refused.ppm" >/dev/null 2>"$dir/refused.err"
    rc=$?
    [ $rc -eq 2 ] && grep -q "the stream has no mesh part" "$dir/refused.err" && [ ! -e "$dir/refused.ppm" ] || problems+="a points stream in a mesh mode: exit $rc, $(oneline <"$dir/refused.err"); "
    "$dir/small/small-view" --stream "$dir/other/other.mcs" --mode shaded --ppm "$dir/refused.ppm" >/dev/null 2>"$dir/refused.err"
    rc=$?
    [ $rc -eq 1 ] && grep -q "stream: its mesh (3002 vertices, 6000 faces) is larger than this viewer's mesh buffers; drawing depth 2" "$dir/refused.err" &&
        [ ! -e "$dir/refused.ppm" ] || problems+="a mesh larger than the viewer's: exit $rc, $(oneline <"$dir/refused.err"); "
    check_problems "mesh: a points-only stream read in a mesh mode (exit 2), a stream whose mesh is larger than the viewer's buffers (exit 1, nothing drawn in the mesh mode): each one line" "$problems"
    # --lod auto: the first frame the finest level that has come, then the level the frame time
    # allows, never above what has come (mc_pmesh_lod_fit_to)
    problems=""
    read -r at level <<<"${mlevels[$((n / 2))]}"
    head -c "$at" "$mmcs" >"$dir/mcut.mcs"
    "$mview" --mode shaded --lod "$level" --yaw 30 --pitch 20 --ppm "$dir/mref.ppm" >/dev/null
    "$mview" --stream "$dir/mcut.mcs" --lod auto --mode shaded --yaw 30 --pitch 20 --ppm "$dir/mcut.ppm" >/dev/null 2>"$dir/mcut.err"
    rc=$?
    [ $rc -eq 1 ] && cmp -s "$dir/mcut.ppm" "$dir/mref.ppm" || problems+="one frame, cut at $at: exit $rc, $(oneline <"$dir/mcut.err"); "
    if command -v tmux >/dev/null; then
        # a frame time no level can miss (10 s): the finest allowed, which is what has come; then one
        # no level can meet (0.01 ms): the base, even once the whole mesh has come
        problems+=$(interactive "$mmcs" "$at" ' shaded \| [0-9]+/[0-9]+ vertices ' \
            " shaded \| $level/$full vertices .*mesh $level of $full vertices" \
            " shaded \| $full/$full vertices .*stream: complete" "$PWD/$mview" --mode shaded --lod auto --target-ms 10000)
        base=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['pmesh']['base_vertices'])" "$dir/mesh/budget.json")
        problems+=$(interactive "$mmcs" "$at" ' shaded \| [0-9]+/[0-9]+ vertices ' \
            " shaded \| $base/$full vertices .*mesh $level of $full vertices" \
            " shaded \| $base/$full vertices .*stream: complete" "$PWD/$mview" --mode shaded --lod auto --target-ms 0.01)
    else
        problems+="tmux missing (make deps installs it); "
    fi
    check_problems "mesh, --lod auto with --stream: one frame of a cut stream is the compiled-in mesh's at the level that came; interactive (tmux): at --target-ms 10000 the level that has come ($level, then $full), at 0.01 the base" "$problems"
    # packed splits (version 3): the same mesh through a viewer whose buffer holds the decoder's state
    problems=""
    if build/bin/modelc "$model" -o "$dir" --name packed --depth 4 --as both --emit stream --stream-splits packed -q \
        >"$dir/packed-bake.log" 2>&1 && link packed; then
        pview=$dir/packed/packed-view
        pmcs=$dir/packed/packed.mcs
        mapfile -t plevels < <(python3 -c "import json,sys; [print(m['at'], m['level']) for m in json.load(open(sys.argv[1]))['stream']['mesh_levels']]" "$dir/packed/budget.json")
        for m in shaded lines; do
            "$pview" --mode $m --yaw 30 --pitch 20 --ppm "$dir/pref-$m.ppm" >/dev/null
            for src in "$pmcs" "$mmcs"; do   # its own stream, and the plain one of the same mesh
                "$pview" --stream "$src" --mode $m --yaw 30 --pitch 20 --ppm "$dir/pwhole.ppm" >"$dir/pwhole.out" 2>&1
                rc=$?
                [ $rc -eq 0 ] && cmp -s "$dir/pwhole.ppm" "$dir/pref-$m.ppm" && grep -q "^stream: mesh level $full of $full after" "$dir/pwhole.out" ||
                    problems+="whole $(basename "$src"), $m: exit $rc, $(oneline <"$dir/pwhole.out"); "
            done
        done
        read -r at level <<<"${plevels[$((${#plevels[@]} / 2))]}"
        head -c "$at" "$pmcs" >"$dir/pcut.mcs"
        "$pview" --mode shaded --lod "$level" --yaw 30 --pitch 20 --ppm "$dir/pref.ppm" >/dev/null
        "$pview" --stream "$dir/pcut.mcs" --mode shaded --yaw 30 --pitch 20 --ppm "$dir/pcut.ppm" >/dev/null 2>"$dir/pcut.err"
        rc=$?
        [ $rc -eq 1 ] && cmp -s "$dir/pcut.ppm" "$dir/pref.ppm" && grep -q "truncated at byte $at; .*mesh level $level$" "$dir/pcut.err" ||
            problems+="cut $at: exit $rc, $(oneline <"$dir/pcut.err"); "
        "$mview" --stream "$pmcs" --mode shaded --ppm "$dir/prefused.ppm" >/dev/null 2>"$dir/prefused.err"
        rc=$?
        [ $rc -eq 1 ] && [ "$(wc -l <"$dir/prefused.err")" = 1 ] && grep -q "stream: size at byte [0-9]*; nothing was drawable" "$dir/prefused.err" || problems+="packed into a plain viewer: exit $rc, $(oneline <"$dir/prefused.err"); "
    else
        problems+="bake or link: $(oneline <"$dir/packed-bake.log"); "
    fi
    check_problems "mesh, packed splits (version 3): the whole stream, and the plain stream of the same mesh, equal to the compiled-in mesh shaded and in lines; cut at the middle batch, exit 1 and --lod's frame at its level; into the plain bake's viewer (its buffer has no room for the decoder): exit 1, one line" "$problems"
else
    notok "mesh bakes with --as both --emit stream and their viewers" "$(cat "$dir/mesh-bake.log" "$dir"/*.link.log 2>/dev/null | tail -n 5 | oneline)"
fi

# refusals: one line each, exit 2, no file
problems=""
for args in "plain/plain-view --stream $mcs" "bunny/bunny-view --stream $dir/none.mcs" "bunny/bunny-view --stream tcp:127.0.0.1:1" \
    "bunny/bunny-view --stream tcp:nohost" "bunny/bunny-view --stream $mcs --bench 3"; do
    rm -f "$dir/refused.ppm"
    # shellcheck disable=SC2086
    "$dir"/$args --ppm "$dir/refused.ppm" >"$dir/refused.out" 2>&1
    rc=$?
    [ $rc -eq 2 ] && [ "$(wc -l <"$dir/refused.out")" = 1 ] && [ ! -e "$dir/refused.ppm" ] ||
        problems+="$args: exit $rc, $(oneline <"$dir/refused.out"); "
done
check_problems "refused with one line, exit 2, no file: a bake without --emit stream, a missing file, a closed port, tcp: without a port, --bench" "$problems"
exit $status
