#!/usr/bin/env bash
# The stream receiver firmware under QEMU, bunny00 on both boards (lm3s6965evb: depth 6 at 96x72 in
# 64 KiB RAM; mps2-an386: depth 7 at 160x120), the model arriving over UART0 (make firmware-stream-run
# feeds the file to QEMU's -serial stdio):
#   - make firmware-stream builds it and its checks pass: no heap, no model symbol linked, receive
#     and frame buffers of the bake's sizes, fits the board, static stack bound within the reservation;
#     arm-none-eabi-nm agrees that no model array is in it
#   - the whole stream: levels 1..D each drawn as it completes, every level's frame checksums equal
#     the host viewer's --checksums --depth d (the baked arrays) and --stream on the same bytes
#     (runtime/front/fw/stream_check.py), "stream complete", exit status 0; the last level's lines
#     compared here once more with the host's --checksums
#   - cut inside a level: after the idle timeout "stream error truncated at byte N" keeping the
#     level before, its checksums equal the host's; a stream larger than the buffer (lm3s6965evb:
#     mps2-an386's real depth-7 stream; mps2-an386: a header claiming one byte more than its
#     buffer): "size at byte 12"; on lm3s6965evb (the reader's checks, the same code on both) a
#     flipped byte: "crc" at that record, the level before kept; version 4 with a valid header CRC:
#     "version at byte 4"; random bytes: "magic"; each without a fault ("done", exit status 1) and
#     as the host viewer's --stream reports it
#   - lm3s6965evb: nothing arrives: "truncated at byte 0" after wait=500 ms; QEMU stopped (SIGSTOP)
#     for 2 s mid-stream, beyond an idle timeout of 1 s, still completes: a stalled emulator does not
#     count as idle time
#   - stream_check.py fails on a run with one checksum changed (the comparison can fail)
# The toolchain comes from make deps: a missing tool is a failure, not a skip.
set -u
cd "$(dirname "$0")/../.." || exit 1
TAP_PREFIX="fw stream: "
. tests/lib.sh
out=build/tests/fw-stream
fresh_dir "$out"
# the receivers' compiles through the shared object cache (tests/cc_cached.sh): the runtime's
# objects are the same for both receivers of a board (and the board's other firmware)
arm_cc="ARM_CC=tests/cc_cached.sh arm-none-eabi-gcc"
model=bunny00

missing=""
for t in arm-none-eabi-gcc arm-none-eabi-nm arm-none-eabi-size qemu-system-arm python3; do
    command -v "$t" >/dev/null || missing="$missing $t"
done
[ -f /usr/lib/picolibc/arm-none-eabi/picolibc.specs ] || missing="$missing picolibc-arm-none-eabi"
check_problems "toolchain installed (gcc-arm-none-eabi, picolibc-arm-none-eabi, qemu-system-arm)" \
    "${missing:+missing:$missing (run make deps)}"
[ -z "$missing" ] || exit 1

# forge IN OUT KIND [ARG]: a damaged copy of a stream (cut N, flip N, version, claim CAP)
forge() {
    python3 - "$@" <<'EOF'
import struct, sys, zlib
src, dst, kind = sys.argv[1:4]
arg = int(sys.argv[4]) if len(sys.argv) > 4 else 0
d = bytearray(open(src, "rb").read())
def reheader(d):   # a valid header CRC, so that only the field itself is wrong
    d[16:20] = struct.pack("<I", zlib.crc32(bytes(d[:16])))
if kind == "cut": d = d[:arg]
elif kind == "flip": d[arg] ^= 0x40
elif kind == "version": d[4:6] = struct.pack("<H", 4); reheader(d)
elif kind == "claim": d[12:16] = struct.pack("<I", arg); reheader(d)
open(dst, "wb").write(d)
EOF
}

# run B NAME STREAM [FW_STREAM_ARGS]: make firmware-stream-run; its output in $out/B.NAME.txt, the
# firmware's lines in $out/B.NAME.run.txt; sets st (make's exit status)
# (MESH=1 in the environment: the receiver built with a mesh, make firmware-stream FW_MESH=1)
run() {
    local b=$1 name=$2 stream=$3 args=${4:-}
    make -s --no-print-directory firmware-stream-run MODEL=$model BOARD="$b" STREAM="$stream" "$arm_cc" \
        FW_STREAM_ARGS="$args" FW_QEMU_TIMEOUT=60 ${MESH:+FW_MESH=1} >"$out/$b.$name.txt" 2>&1
    st=$?
    cp "build/fw/$b-stream${MESH:+-mesh}/run.txt" "$out/$b.$name.run.txt" 2>/dev/null || : >"$out/$b.$name.run.txt"
}
final() { grep -E '^stream (complete|error)' "$out/$1.$2.run.txt" | oneline; }
# expect B NAME WANT(regex for the final line) LABEL: the run compared equal with the host and ended so
expect() {
    local b=$1 name=$2 want=$3 label=$4 f
    f=$(final "$b" "$name")
    check_problems "$b: $label: \"${f:-no final line}\", no fault, as the host viewer's --stream" \
        "$([ $st -eq 0 ] && [[ $f =~ $want ]] && grep -qx done "$out/$b.$name.run.txt" ||
            echo "make exit $st, final '$f': $(grep -v '^frame' "$out/$b.$name.txt" | tail -4 | oneline)")"
}

for b in lm3s6965evb mps2-an386; do
    dir=build/fw/$b-stream
    elf=$dir/$model-stream.elf
    t0=$(date +%s)
    make -s --no-print-directory -j2 firmware-stream MODEL=$model BOARD=$b "$arm_cc" >"$out/$b.build.txt" 2>&1
    bst=$?
    grep -E '^(ok|not ok) - fw: ' "$out/$b.build.txt" | sed "s/^\(ok\|not ok\) - fw: /\1 - fw stream: $b: /"
    grep -q '^not ok' "$out/$b.build.txt" && status=1
    if [ $bst -ne 0 ] || [ ! -f "$elf" ]; then
        notok "$b: make firmware-stream BOARD=$b" "exit $bst: $(grep -v '^ok' "$out/$b.build.txt" | tail -5 | oneline)"
        continue
    fi
    figures=$(sed -n 's/^firmware [^:]*: //p' "$out/$b.build.txt")
    ok "$b: make firmware-stream builds $elf ($(($(date +%s) - t0)) s): $figures"
    syms=$(arm-none-eabi-nm "$elf" | awk '{print $NF}' | grep -E "^(mc_model_$model|mc_octree_$model|mc_${model}_.*|mc_app_model)$" | oneline)
    check_problems "$b: arm-none-eabi-nm: no model symbol in the image (the model comes over the UART)" "${syms:+found: $syms}"

    bake=$dir/$model
    mcs=$bake/$model.mcs
    read -r depth cap at1 at2 < <(python3 -c '
import json, sys
b = json.load(open(sys.argv[1])); s = b["stream"]; a = s["drawable_at"]; d = b["depth"]
print(d, s["bytes"], a[d - 3], a[d - 2])' "$bake/budget.json")
    # ---- the whole stream --------------------------------------------------------------------------
    t0=$(date +%s)
    run $b full "$mcs"
    secs=$(($(date +%s) - t0))
    levels=$(grep -c '^level ' "$out/$b.full.run.txt")
    expect $b full "^stream complete: depth $depth, $cap bytes$" \
        "the whole stream ($cap bytes, $secs s): levels 1..$depth drawn as they complete, each level's checksums equal the host's"
    check_problems "$b: $levels levels of $(grep -c '^frame ' "$out/$b.full.run.txt") frame lines, every render MC_OK" \
        "$([ "$levels" -eq "$depth" ] && ! grep '^frame ' "$out/$b.full.run.txt" | grep -qv ' rc 0 ' || echo "$levels levels")"
    grep '^frame .* depth '"$depth"' level ' "$out/$b.full.run.txt" >"$out/$b.last.txt"
    n=$(wc -l <"$out/$b.last.txt")
    "$bake/$model-view" --checksums --depth "$depth" | head -n "$n" >"$out/$b.host-last.txt"
    check_problems "$b: depth $depth's $n frame lines equal the host viewer's --checksums (the baked model)" \
        "$([ "$n" -gt 0 ] && cmp -s "$out/$b.last.txt" "$out/$b.host-last.txt" || diff "$out/$b.last.txt" "$out/$b.host-last.txt" | head -3 | oneline)"

    # the comparison fails on one changed checksum
    sed '0,/fnv1a /s/fnv1a \(.\)/fnv1a X\1/' "$out/$b.full.run.txt" >"$out/$b.tampered.txt"
    python3 runtime/front/fw/stream_check.py --run "$out/$b.tampered.txt" --status 0 --view "$bake/$model-view" \
        --stream "$mcs" --work "$out/$b.tampered" >"$out/$b.tampered.out" 2>&1
    check_problems "$b: stream_check.py fails on a run with one checksum changed" \
        "$([ $? -ne 0 ] && grep -q 'differ' "$out/$b.tampered.out" || oneline <"$out/$b.tampered.out")"

    # ---- damaged streams ---------------------------------------------------------------------------
    cut=$(((at1 + at2) / 2))
    forge "$mcs" "$out/$b.cut.mcs" cut $cut
    t0=$(date +%s)
    run $b cut "$out/$b.cut.mcs"
    expect $b cut "^stream error truncated at byte $cut after $cut bytes \(no byte for 2000 ms\); keeping depth $((depth - 2))$" \
        "cut at byte $cut inside level $((depth - 1)) ($(($(date +%s) - t0)) s with the 2 s idle timeout): level $((depth - 2)) kept"
    # the reader's own refusals, the same code on both boards, on lm3s6965evb only; the cut above
    # (each board's UART driver and idle timeout) and the oversized stream below (each board's
    # buffer) on both
    if [ $b = lm3s6965evb ]; then
        flip=$(((at1 + at2) / 2))
        forge "$mcs" "$out/$b.flip.mcs" flip $flip
        run $b flip "$out/$b.flip.mcs"
        expect $b flip "^stream error crc at byte $at1 after [0-9]+ bytes; keeping depth $((depth - 2))$" \
            "byte $flip flipped (level $((depth - 1))'s record at $at1)"
        forge "$mcs" "$out/$b.version.mcs" version
        run $b version "$out/$b.version.mcs"
        expect $b version "^stream error version at byte 4 after 20 bytes; keeping depth 0 \(nothing drawable\)$" \
            "version 4 (header CRC valid)"
        python3 -c 'import random, sys; random.seed(12); sys.stdout.buffer.write(bytes(random.randrange(256) for _ in range(3000)))' \
            >"$out/$b.garbage.mcs"
        run $b garbage "$out/$b.garbage.mcs"
        expect $b garbage "^stream error (magic|crc) at byte 0 after 20 bytes; keeping depth 0 \(nothing drawable\)$" \
            "3,000 random bytes"
    fi
    if [ $b = lm3s6965evb ]; then
        big=build/fw/mps2-an386-stream/$model/$model.mcs
        make -s --no-print-directory build/fw/mps2-an386-stream/$model/budget.json MODEL=$model BOARD=mps2-an386 >/dev/null 2>&1
        what="mps2-an386's depth-7 stream ($(stat -c %s "$big" 2>/dev/null) bytes)"
    else
        big=$out/$b.big.mcs
        forge "$mcs" "$big" claim $((cap + 1))
        what="a header claiming $((cap + 1)) bytes"
    fi
    run $b big "$big"
    expect $b big "^stream error size at byte 12 after 20 bytes; keeping depth 0 \(nothing drawable\)$" \
        "$what against the $cap-byte buffer refused"
    [ $b = lm3s6965evb ] || continue

    # ---- the end of input and host stalls ------------------------------------------------------------
    : >"$out/empty.mcs"
    run $b empty "$out/empty.mcs" wait=500
    expect $b empty "^stream error truncated at byte 0 after 0 bytes \(no byte for 500 ms\); keeping depth 0 \(nothing drawable\)$" \
        "nothing arrives (wait=500)"
    # QEMU itself, fed through a pipe, stopped for 2 s after 5,000 bytes, its idle timeout 1 s
    qemu=$(mkvar FW_STREAM_QEMU MODEL=$model BOARD=$b FW_STREAM_ARGS=idle=1000 | sed 's/^timeout [0-9]* //')
    rm -f "$out/qemu.pid"
    t0=$(date +%s)
    # shellcheck disable=SC2086
    {
        head -c 5000 "$mcs"
        sleep 0.5
        kill -STOP "$(cat "$out/qemu.pid")"
        sleep 2
        kill -CONT "$(cat "$out/qemu.pid")"
        tail -c +5001 "$mcs"
    } | (echo $BASHPID >"$out/qemu.pid"; exec $qemu) >"$out/$b.stall.run.txt" 2>&1
    qst=$?
    python3 runtime/front/fw/stream_check.py --run "$out/$b.stall.run.txt" --status $qst --view "$bake/$model-view" \
        --stream "$mcs" --work "$out/$b.stall" >"$out/$b.stall.txt" 2>&1
    st=$?
    expect $b stall "^stream complete: depth $depth, $cap bytes$" \
        "QEMU stopped 2 s mid-stream, beyond its 1 s idle timeout ($(($(date +%s) - t0)) s): the stream still completes"
done

# ---- a mesh over the UART (make firmware-stream FW_MESH=1) ----------------------------------------------
# lm3s6965evb: 600 faces, plain splits; mps2-an386: 4,000 faces, packed splits (boards/B.mk); fandisk,
# whose creases the line frames draw too and whose bake takes a fifth of bunny00's
export MESH=1
model=fandisk
for b in lm3s6965evb mps2-an386; do
    dir=build/fw/$b-stream-mesh
    make -s --no-print-directory -j2 firmware-stream MODEL=$model BOARD=$b FW_MESH=1 "$arm_cc" >"$out/$b.mesh-build.txt" 2>&1
    bst=$?
    grep -E '^(ok|not ok) - fw: ' "$out/$b.mesh-build.txt" | sed "s/^\(ok\|not ok\) - fw: /\1 - fw stream: $b mesh: /"
    grep -q '^not ok' "$out/$b.mesh-build.txt" && status=1
    if [ $bst -ne 0 ] || [ ! -f "$dir/$model-stream.elf" ]; then
        notok "$b: make firmware-stream BOARD=$b FW_MESH=1" "exit $bst: $(grep -v '^ok' "$out/$b.mesh-build.txt" | tail -5 | oneline)"
        continue
    fi
    bake=$dir/$model
    mcs=$bake/$model.mcs
    read -r depth cap faces lines_at < <(python3 -c '
import json, sys
b = json.load(open(sys.argv[1])); s = b["stream"]
print(b["depth"], s["bytes"], b["pmesh"]["faces"], s["mesh_lines_at"])' "$bake/budget.json")
    run $b mesh "$mcs"
    expect $b mesh "^stream complete: depth $depth, $cap bytes$" \
        "a $faces-face mesh stream ($cap bytes, $(grep -o 'stream-splits [a-z]*' "$dir/$model.opts")): the points' levels and the mesh frames equal the host's (--stream, --checksums)"
    # the mesh drawn as it came: a block of the views' mesh frames at each level budget.json says a
    # mesh record brings (mesh_levels: level and byte), then the whole mesh after its adjacency
    m=$(grep -c '^mesh frame .* rc 0 ' "$out/$b.mesh.run.txt")
    views=$("$bake/$model-view" --checksums | grep -c '^mesh frame ')
    got=$(sed -n 's/^mesh level \([0-9]*\) of [0-9]* drawable after \([0-9]*\) bytes$/\1@\2/p' "$out/$b.mesh.run.txt" | oneline)
    want=$(python3 -c 'import json, sys; print(" ".join("%d@%d" % (m["level"], m["at"]) for m in json.load(open(sys.argv[1]))["stream"]["mesh_levels"]))' "$bake/budget.json")
    check_problems "$b: the mesh drawn at each level as it came ($got: level@byte, budget.json's mesh_levels), then \"mesh complete after $lines_at bytes\" (mesh_lines_at); $m mesh frames, $views a block, every render MC_OK" \
        "$([ "$got" = "$want" ] && grep -qx "mesh complete after $lines_at bytes" "$out/$b.mesh.run.txt" && [ "$views" -gt 0 ] &&
            [ "$m" -eq $((views * ($(wc -w <<<"$want") + 1))) ] || echo "levels $got, budget.json $want; $m mesh frames")"
    [ $b = lm3s6965evb ] || continue
    # the comparison fails on one changed mesh checksum
    sed '0,/^mesh frame .*fnv1a /s/fnv1a \(.\)/fnv1a X\1/' "$out/$b.mesh.run.txt" >"$out/$b.mesh-tampered.txt"
    python3 runtime/front/fw/stream_check.py --run "$out/$b.mesh-tampered.txt" --status 0 --view "$bake/$model-view" \
        --stream "$mcs" --work "$out/$b.mesh-tampered" >"$out/$b.mesh-tampered.out" 2>&1
    check_problems "$b: stream_check.py fails on a run with one mesh checksum changed" \
        "$([ $? -ne 0 ] && grep -q 'mesh frames differ' "$out/$b.mesh-tampered.out" || oneline <"$out/$b.mesh-tampered.out")"
    # cut inside the adjacency, the mesh's last record: its levels came (and were drawn), its line
    # styles did not
    cut=$((lines_at - 10))
    forge "$mcs" "$out/$b.mesh-cut.mcs" cut $cut
    run $b mesh-cut "$out/$b.mesh-cut.mcs" idle=500
    expect $b mesh-cut "^stream error truncated at byte $cut after $cut bytes \(no byte for 500 ms\); keeping depth $depth$" \
        "cut at byte $cut inside the mesh's adjacency: the mesh's levels drawn shaded, never its lines, as the host's --stream --checksums"
    # a byte flipped inside a record of splits: the levels before it drawn, none after (the CRC)
    read -r at2 lv1 < <(python3 -c 'import json, sys; m = json.load(open(sys.argv[1]))["stream"]["mesh_levels"]
print(m[2]["at"], m[1]["level"])' "$bake/budget.json")
    flip=$((at2 - 20))
    forge "$mcs" "$out/$b.mesh-flip.mcs" flip $flip
    run $b mesh-flip "$out/$b.mesh-flip.mcs"
    last_level=$(sed -n 's/^mesh level \([0-9]*\) of .*/\1/p' "$out/$b.mesh-flip.run.txt" | tail -n 1)
    expect $b mesh-flip "^stream error crc at byte [0-9]+ after [0-9]+ bytes; keeping depth [0-9]+$" \
        "byte $flip flipped in the mesh record ending at $at2: the mesh drawn up to level ${last_level:-none} (budget.json: $lv1 before that record), no further"
    check_problems "$b: after the flipped mesh record, no mesh level beyond $lv1 drawn" \
        "$([ "${last_level:-0}" = "$lv1" ] || echo "last mesh level drawn ${last_level:-none}")"
    # a mesh of more vertices than this receiver's memory, in a stream that fits its buffer (the
    # octree at depth 1 leaves room for a few more faces)
    big=$out/$b.mesh-big
    cap_buf=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["stream"]["buffer"])' "$bake/budget.json")
    for f in 616 610 604; do
        rm -rf "$big"
        build/bin/modelc "$(model_file $model)" -o "$big" --name $model -q --depth 1 --screen 96x72 --as both \
            --max-faces $f --emit stream >"$out/$b.mesh-big.bake.txt" 2>&1
        read -r buf_big verts_big < <(python3 -c 'import json,sys; b = json.load(open(sys.argv[1]))
print(b["stream"]["buffer"], b["pmesh"]["vertices"])' "$big/$model/budget.json")
        [ "$buf_big" -le "$cap_buf" ] && break
    done
    run $b mesh-big "$big/$model/$model.mcs"
    expect $b mesh-big "^stream error mesh-size at byte [0-9]+ after [0-9]+ bytes; keeping depth 0 \(nothing drawable\)$" \
        "a $f-face mesh ($verts_big vertices, a $buf_big-byte buffer) against memory for $faces faces refused, as the host viewer refuses it"
done
exit ${status:-0}
