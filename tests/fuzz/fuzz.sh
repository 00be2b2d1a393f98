#!/usr/bin/env bash
# make fuzz: each fuzz target (build/fuzz/fuzz-TARGET, built by make fuzz-build) under libFuzzer for
# FUZZ_SECONDS, from seeds written now (tests/fuzz/seeds.py from the catalogue, and the inputs of
# tests/gen/errors.sh's malformed-input table); then every finding (crash, sanitizer report, abort,
# timeout, allocation over the limit) minimized and, one per distinct report, added to
# tests/fuzz/regress/TARGET/, which tests/fuzz/suite.sh replays in make test.
#
# usage: tests/fuzz/fuzz.sh [TARGET...]       (default: off obj ply stl xyz cao gltf glb bake track_input)
#   FUZZ_SECONDS=600   seconds per target
#   FUZZ_JOBS=1        libFuzzer worker processes per target (-fork)
#   FUZZ_TIMEOUT=10    seconds one input may take before it is a hang
#   FUZZ_RSS_MB=2048   resident memory, and FUZZ_MALLOC_MB=512 one allocation, before it is a finding
#   FUZZ_MAX_LEN=4096  largest input in bytes: tiny files, where a bad header does the most harm
#   FUZZ_WORK=build/fuzz  where seeds, corpus and raw findings go (the targets are build/fuzz/fuzz-*)
# Exits 1 when a target found something not already in tests/fuzz/regress/.
set -u
cd "$(dirname "$0")/../.." || exit 1
. tests/lib.sh
SECS=${FUZZ_SECONDS:-600}
JOBS=${FUZZ_JOBS:-1}
TIMEOUT=${FUZZ_TIMEOUT:-10}
RSS_MB=${FUZZ_RSS_MB:-2048}
MALLOC_MB=${FUZZ_MALLOC_MB:-512}
MAX_LEN=${FUZZ_MAX_LEN:-4096}
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(off obj ply stl xyz cao gltf glb bake track_input stream)
bins=build/fuzz
dir=${FUZZ_WORK:-build/fuzz}
exts=(off obj ply stl xyz cao)   # the bake target's format byte, as in fuzz_bake.cpp
limits=(-timeout="$TIMEOUT" -rss_limit_mb="$RSS_MB" -malloc_limit_mb="$MALLOC_MB")
export ASAN_OPTIONS="abort_on_error=1:halt_on_error=1:detect_leaks=1:allocator_may_return_null=0"

# ---- seeds ------------------------------------------------------------------------------------
seeds=$dir/seeds
rm -rf "$seeds"
mkdir -p "$seeds/bake"
python3 tests/fuzz/seeds.py build/models "$seeds" || { echo "fuzz: tests/fuzz/seeds.py failed" >&2; exit 2; }
# the malformed-input table: errors.sh run with a stand-in generator that keeps each input file
collect=$dir/collect-input.sh
cat >"$collect" <<'SH'
#!/usr/bin/env bash
f=$1; ext=$(echo "${f##*.}" | tr 'A-Z' 'a-z')
[ -f "$f" ] && [ -d "$FUZZ_SEEDS/$ext" ] && cp "$f" "$FUZZ_SEEDS/$ext/errors-$(basename "$f")"
exit 1
SH
chmod +x "$collect"
FUZZ_SEEDS=$PWD/$seeds bash tests/gen/errors.sh "$PWD/$collect" >/dev/null 2>&1
for i in "${!exts[@]}"; do
    for f in "$seeds/${exts[$i]}"/errors-*; do
        [ -f "$f" ] && { printf "\\x$(printf %02x "$i")"; cat "$f"; } >"$seeds/bake/$(basename "$f")"
    done
done

# the tracker's input readers (track_input, tests/fuzz/fuzz_track_input.c; its findings are
# replayed by tests/unit/test_track_input.c): small PGMs (P5, P2, 16-bit, a crop of ViSP's cube
# sequence), ViSP's tracker settings and pose (Debian visp-images-data, when installed), a camera
# file's XML, an orientation file and the command-line forms
ts=$seeds/track_input
mkdir -p "$ts"
printf 'P5\n# seed\n4 2\n255\n\001\002\003\004\375\376\377\000' >"$ts/p5.pgm"
printf 'P2\n3 2\n15\n0 1 2\n# c\n13 14 15\n' >"$ts/p2.pgm"
printf 'P5 2 1 65535\n\001\002\377\377' >"$ts/p5-16.pgm"
visp=/usr/share/visp-images-data/ViSP-images/mbt
[ -f "$visp/cube/image0000.pgm" ] && { printf 'P5\n32 16\n255\n'; tail -c +16 "$visp/cube/image0000.pgm" | head -c 512; } >"$ts/cube.pgm"
for f in cube.xml cube.0.pos; do [ -f "$visp/$f" ] && cp "$visp/$f" "$ts/"; done
printf '<root><camera><model><px>600</px><py>601</py><u0>320</u0><v0>240</v0></model></camera></root>\n' >"$ts/camera.xml"
printf '0.02 0.1 0.5\n# theta u\n2.1 1.1 -0.4\n' >"$ts/pose.pos"
printf '# theta u per frame\n0 0 0\n0.1 -0.2 0.3 # c\n\n1e-3 0 3.14\n' >"$ts/orient.txt"
printf '547.7,542.1,338.7,234.5' >"$ts/camera.txt"
printf '0.02,0.1,0.5,2.1,1.1,-0.4' >"$ts/pose.txt"

# the stream reader (stream, tests/fuzz/fuzz_stream.c; its findings are replayed by
# tests/stream/suite.sh): small bakes' streams (--emit stream), each read whole and with its CRCs
# rewritten (the target's first byte)
ss=$seeds/stream
mkdir -p "$ss"
for spec in "bunny00 --depth 5" "kitten --depth 4 --palette 1" "bunny00 --depth 3 --as both --max-faces 300" \
    "bunny00 --depth 3 --as both --max-faces 300 --stream-splits packed"; do
    read -r m args <<<"$spec"
    seed=$m${args//[^0-9]/}
    [[ $args == *packed ]] && seed=${seed}packed
    # shellcheck disable=SC2086
    build/bin/modelc "$(model_file "$m")" -o "$dir/stream-seeds" --name "s_$m" --emit stream -q $args &&
        for b in 0 3; do { printf "\\x0$b"; cat "$dir/stream-seeds/s_$m/s_$m.mcs"; } >"$ss/$seed-$b.in"; done
done

# signature FILE TARGET: what a finding's report says, without addresses or sizes, and the first
# frame in the generator's own code: two findings with one signature are one bug
signature() {
    "$bins/fuzz-$2" "${limits[@]}" "$1" >"$dir/sig.log" 2>&1
    local what frame
    what=$(grep -m1 -oE 'ERROR: (AddressSanitizer|LeakSanitizer|libFuzzer): [a-z-]+|runtime error: [^0-9]*|terminate called [a-z ]*|CGAL ERROR: [a-z ]+|ERROR: libFuzzer: [a-z-]+' "$dir/sig.log")
    frame=$(grep -m1 -E '^ *#[0-9]+ .* in .*(/|^)gen/' "$dir/sig.log" | sed -E 's/.* in ([^ ]+).*/\1/')
    # else the first frame outside libFuzzer, the sanitizers and libc (a library's own code)
    [ -n "$frame" ] || frame=$(grep -E '^ *#[0-9]+ 0x[0-9a-f]+ in ' "$dir/sig.log" |
        grep -vE 'fuzzer::|__sanitizer|__asan|__ubsan|libc\.so|compiler-rt|/libFuzzer|in (abort|raise|__GI_|__pthread_kill)' |
        head -n 1 | sed -E 's/.* in ([^ ]+).*/\1/')
    [ -n "$what" ] || return 1   # not reproducible
    echo "$what @ ${frame:-?}"
}

# regress_name FILE TARGET KIND: the regression file's name: KIND-SHA.EXT, the bake's format byte
# turned into the extension (and ".views" for bit 7, ".mesh" for bit 6)
install_finding() {
    local f=$1 t=$2 kind=$3 sha ext b views="" mesh=""
    sha=$(sha1sum "$f" | cut -c1-12)
    mkdir -p "tests/fuzz/regress/$t"
    if [ "$t" = bake ]; then
        b=$(head -c 1 "$f" | od -An -tu1 | tr -d ' ')
        [ -n "$b" ] || return
        [ $((b & 128)) -ne 0 ] && views=.views
        [ $((b & 64)) -ne 0 ] && mesh=.mesh
        ext=${exts[$(((b & 63) % ${#exts[@]}))]}
        tail -c +2 "$f" >"tests/fuzz/regress/$t/$kind-$sha$views$mesh.$ext"
        echo "tests/fuzz/regress/$t/$kind-$sha$views$mesh.$ext"
    else
        cp "$f" "tests/fuzz/regress/$t/$kind-$sha.$t"
        echo "tests/fuzz/regress/$t/$kind-$sha.$t"
    fi
}
# the bake target's form of a regression file (the format byte back in front)
bake_input() {
    local f=$1 base ext i b=0
    base=$(basename "$f")
    ext=${base##*.}
    for i in "${!exts[@]}"; do [ "${exts[$i]}" = "$ext" ] && b=$i; done
    case $base in *.views.*) b=$((b | 128)) ;; esac
    case $base in *.mesh.*) b=$((b | 64)) ;; esac
    { printf "\\x$(printf %02x "$b")"; cat "$f"; }
}

new_total=0
for t in "${targets[@]}"; do
    bin=$bins/fuzz-$t
    [ -x "$bin" ] || { echo "fuzz: $bin missing (make fuzz-build)" >&2; exit 2; }
    corpus=$dir/corpus/$t
    found=$dir/findings/$t
    mkdir -p "$corpus" "$seeds/$t"
    rm -rf "$found"
    mkdir -p "$found"
    close=0
    [ "$t" = bake ] && close=3   # the bake's own "modelc: ..." lines would flood the log
    echo "fuzz: $t for $SECS s ($JOBS job(s)), seeds $seeds/$t, corpus $corpus"
    nice -n 10 "$bin" -fork="$JOBS" -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
        -max_total_time="$SECS" -max_len="$MAX_LEN" "${limits[@]}" -use_value_profile=1 \
        -close_fd_mask=$close -artifact_prefix="$found/" -print_final_stats=1 \
        "$corpus" "$seeds/$t" >"$dir/$t.log" 2>&1
    grep -E '^#[0-9]+:? .*cov:' "$dir/$t.log" | tail -n 1 | sed "s/^/fuzz: $t: /"
    # the signatures already covered by regression files
    known=()
    for f in tests/fuzz/regress/"$t"/*; do
        [ -f "$f" ] || continue
        if [ "$t" = bake ]; then bake_input "$f" >"$dir/known.in"; else cp "$f" "$dir/known.in"; fi
        s=$(signature "$dir/known.in" "$t") && known+=("$s")
    done
    new=0
    for a in "$found"/crash-* "$found"/timeout-* "$found"/oom-* "$found"/leak-*; do
        [ -f "$a" ] || continue
        kind=$(basename "$a" | cut -d- -f1)
        min=$a.min
        # shellcheck disable=SC2086
        nice -n 10 "$bin" -minimize_crash=1 -max_total_time=60 "${limits[@]}" -exact_artifact_path="$min" \
            "$a" >"$a.minimize.log" 2>&1
        [ -s "$min" ] || cp "$a" "$min"
        s=$(signature "$min" "$t") || { echo "fuzz: $t: $a does not reproduce alone (kept in $found)"; continue; }
        seen=0
        for k in "${known[@]}"; do [ "$k" = "$s" ] && seen=1; done
        [ "$seen" = 1 ] && continue
        known+=("$s")
        f=$(install_finding "$min" "$t" "$kind")
        echo "fuzz: $t: new finding $f: $s"
        new=$((new + 1))
    done
    echo "fuzz: $t: $new new finding(s)"
    new_total=$((new_total + new))
done
[ "$new_total" -eq 0 ] || { echo "fuzz: $new_total new finding(s) in tests/fuzz/regress/: commit them with the fix"; exit 1; }
echo "fuzz: no new findings"
