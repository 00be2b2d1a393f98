#!/usr/bin/env bash
# The viewer's interactive mode, driven in a real pseudo-terminal: a detached tmux session of fixed
# size runs the viewer, send-keys types, capture-pane reads the screen back (-e keeps the colours).
#
#   tests/host/interactive.sh [VIEWER]      default build/bunny00/bunny00-view
#
# One line per check, "ok - interactive: ..." or "not ok - interactive: ...: why"; exit 0 only if
# all passed. Every wait polls up to a deadline instead of sleeping a fixed time, so a slow, loaded
# machine passes too; only the quit check has a tight limit (one second), as the viewer promises.
set -u
# a VIEWER given is relative to the caller's directory, the default to the repository's
viewer=${1:+$(realpath -m -- "$1")}
cd "$(dirname "$0")/../.." || exit 1
viewer=${viewer:-$PWD/build/bunny00/bunny00-view}
name=$(basename "$viewer")
name=${name%-view}
unset TMUX   # a private server, even when run from inside tmux
export LC_ALL=C.UTF-8 TERM=${TERM:-xterm-256color}
[ "$TERM" = dumb ] && TERM=xterm-256color

tmpdir=$(mktemp -d)
sock=mctest$$
cleanup() {
    tmux -L "$sock" kill-server 2>/dev/null
    rm -f "${TMUX_TMPDIR:-/tmp}/tmux-$(id -u)/$sock"   # kill-server leaves the socket file behind
    rm -rf "$tmpdir"
}
trap cleanup EXIT
trap 'exit 1' INT TERM HUP

failed=0
ok() { echo "ok - interactive: $1"; }
not_ok() {
    echo "not ok - interactive: $1: $2"
    failed=1
}

# Dead panes stay (their exit status and screen can be inspected); no status bar, so the pane is the
# whole window.
printf 'set -g remain-on-exit on\nset -g status off\n' >"$tmpdir/tmux.conf"
tm() { tmux -u -L "$sock" -f "$tmpdir/tmux.conf" "$@"; }

now_ms() {
    local t=${EPOCHREALTIME//[.,]/}
    echo $((t / 1000))
}

# poll SECONDS COMMAND...: run COMMAND every 50 ms until it succeeds or SECONDS (whole) pass.
poll() {
    local deadline=$(($(now_ms) + $1 * 1000))
    shift
    until "$@"; do
        [ "$(now_ms)" -ge "$deadline" ] && return 1
        sleep 0.05
    done
}

screen() { tm capture-pane -p -t "$1" 2>/dev/null; }
# The status line, e.g. " bunny00 | points | depth 7/8 at 100x78 | 0.4 ms | 52572 points | zoom 1.00 | q quits, ..."
status() { screen "$1" | grep -E ' depth [0-9]+/[0-9]+ ' | tail -n 1; }
status_field() { status "$1" | sed -nE "s/.* $2 ([0-9.]+).*/\1/p"; }   # field after a word
depth_shown() { status "$1" | sed -nE 's/.* depth ([0-9]+)\/[0-9]+ .*/\1/p'; }
# The picture: every row but the status line, with its colour escapes.
picture() { tm capture-pane -p -e -t "$1" 2>/dev/null | grep -vE ' depth [0-9]+/[0-9]+ '; }
pane() { tm display-message -p -t "$1" "$2" 2>/dev/null; }

# start_viewer SESSION: the viewer in a 100x40 pane, under a wrapper that records the terminal
# settings before and after it, its pid and exit status (SESSION.pid, .rc, .stty0, .stty1), then
# keeps the pane open so the screen the viewer left behind can be inspected.
cat >"$tmpdir/run.sh" <<'EOF'
#!/bin/sh
stty -g >"$1.stty0"
sh -c 'echo $$ >"$1"; exec "$2"' sh "$1.pid" "$2"
echo $? >"$1.rc"
stty -g >"$1.stty1"
exec sleep 600
EOF
start_viewer() {
    tm new-session -d -s "$1" -x 100 -y 40 \
        "sh $(printf '%q' "$tmpdir/run.sh") $(printf '%q' "$tmpdir/$1") $(printf '%q' "$viewer")"
}
exited() { [ -s "$tmpdir/$1.rc" ] && [ -s "$tmpdir/$1.stty1" ]; }
# restored SESSION RC: after the viewer exited with status RC, the terminal is as before it started
restored() {
    local rc state
    rc=$(cat "$tmpdir/$1.rc")
    state=$(pane "$1" 'alt=#{alternate_on} cursor=#{cursor_flag}')
    if [ "$rc" != "$2" ]; then
        echo "exit status $rc, expected $2"
    elif [ "$state" != "alt=0 cursor=1" ]; then
        echo "$state: expected alt=0 (alternate screen left) cursor=1 (cursor shown)"
    elif ! cmp -s "$tmpdir/$1.stty0" "$tmpdir/$1.stty1"; then
        echo "the terminal settings (stty -g) differ from before"
    elif screen "$1" | grep -q '▀'; then
        echo "the viewer's picture is still on the screen"
    fi
}

if [ ! -x "$viewer" ]; then
    not_ok "viewer" "$viewer is missing or not executable"
    exit 1
fi
if ! command -v tmux >/dev/null; then
    not_ok "tmux" "tmux is not installed (make deps)"
    exit 1
fi

# ---- (a) startup: half-block cells and a status line naming the model ------------------------------
startup() {
    has_picture() { screen v | grep -q '▀' && status v | grep -q " $name "; }
    if poll 10 has_picture; then
        ok "startup shows half-block cells and a status line naming $name"
        return 0
    fi
    not_ok "startup shows half-block cells and a status line naming $name" \
        "screen after 10 s: $(screen v | grep -c '▀') rows with half blocks, status '$(status v)'"
    return 1
}

# ---- (b) the model turns by itself before any key ----------------------------------------------------
auto_turn() {
    local first
    first=$(picture v)
    picture_changed() { [ "$(picture v)" != "$first" ]; }
    if poll 5 picture_changed; then
        ok "the model turns by itself before any key (depth $(depth_shown v) while turning)"
    else
        not_ok "the model turns by itself before any key" "the picture did not change within 5 s"
    fi
}

# ---- (c) held arrows draw one level coarser, released at the fine level -----------------------------
# The fine level is the level of detail's for the frame size (one pixel; the viewer --png at the size
# the status line gives draws it too), the coarse one twice that bound: one level coarser.
shows_depth() { [ "$(depth_shown v)" = "$1" ]; }

# One key stops the automatic turn; once it counts as released the fine level is drawn and stays.
first_key() {
    local size
    tm send-keys -t v Left
    size=$(status v | sed -nE 's/.* depth [0-9]+\/[0-9]+ at ([0-9]+x[0-9]+) .*/\1/p')
    full=$("$viewer" --size "$size" --png "$tmpdir/fine.png" 2>/dev/null | sed -nE 's/.* depth ([0-9]+) .*/\1/p')
    coarse=$((full > 1 ? full - 1 : 1))
    if [ -z "$full" ]; then
        not_ok "a key stops the automatic turn" "no frame size in the status line: '$(status v)'"
    elif poll 5 shows_depth "$full"; then
        ok "a key stops the automatic turn and the fine level $full (the viewer's for ${size}) is drawn"
    else
        not_ok "a key stops the automatic turn" "status after 5 s: '$(status v)' (expected depth $full)"
    fi
}

# hold KEY: send KEY every 50 ms, like a terminal's auto-repeat, for up to 3 s or until the coarse
# depth is on screen plus a few more repeats; then release and wait for the full depth.
hold() {
    local key=$1 seen=0 before end
    before=$(picture v)
    end=$(($(now_ms) + 3000))
    while [ "$(now_ms)" -lt "$end" ]; do
        tm send-keys -t v "$key"
        if [ "$seen" -eq 0 ] && shows_depth "$coarse"; then
            seen=1
            end=$(($(now_ms) + 300))   # keep holding a little: the picture must move
        fi
        sleep 0.05
    done
    if [ "$seen" -eq 0 ]; then
        not_ok "holding $key draws depth $coarse" "status while held: '$(status v)'"
    elif ! poll 5 shows_depth "$full"; then
        not_ok "releasing $key draws depth $full" "status 5 s after release: '$(status v)'"
    elif [ "$(picture v)" = "$before" ]; then
        not_ok "holding $key turns the model" "the picture is the same as before"
    else
        ok "holding $key turns the model at depth $coarse, releasing it draws depth $full"
    fi
}

# ---- (d) + zooms in, r resets -----------------------------------------------------------------------
zoom_keys() {
    local zoom0 zoom1
    zoom0=$(status_field v zoom)
    if [ -z "$zoom0" ]; then
        not_ok "+ zooms in" "no zoom in the status line: '$(status v)'"
        return
    fi
    zoom_is() { [ "$(status_field v zoom)" = "$1" ]; }
    zoom_not() { local z; z=$(status_field v zoom); [ -n "$z" ] && [ "$z" != "$1" ]; }
    tm send-keys -t v -l +
    if poll 5 zoom_not "$zoom0"; then
        zoom1=$(status_field v zoom)
        if awk -v a="$zoom0" -v b="$zoom1" 'BEGIN { exit !(b > a) }'; then
            ok "+ zooms in (zoom $zoom0 -> $zoom1)"
        else
            not_ok "+ zooms in" "zoom went from $zoom0 to $zoom1"
        fi
    else
        not_ok "+ zooms in" "zoom still $zoom0 5 s after +: '$(status v)'"
    fi
    tm send-keys -t v -l r
    if poll 5 zoom_is "$zoom0"; then
        ok "r resets the view (zoom $zoom0)"
    else
        not_ok "r resets the view" "status 5 s after r: '$(status v)'"
    fi
}

# ---- (e) q quits at once and leaves the terminal as it found it -----------------------------------
quit_key() {
    local t0 why
    if exited v; then
        not_ok "q quits" "the viewer had already exited (status $(cat "$tmpdir/v.rc")) before q"
        return
    fi
    t0=$(now_ms)
    tm send-keys -t v -l q
    if ! poll 1 exited v; then
        not_ok "q quits within a second" "still running after 1 s: '$(status v)'"
        return
    fi
    ok "q quits (exited within $(($(now_ms) - t0)) ms)"
    why=$(restored v 0)
    if [ -z "$why" ]; then
        ok "the terminal is restored after q (alternate screen left, cursor shown, stty, status 0)"
    else
        not_ok "the terminal is restored after q" "$why"
    fi
}

start_viewer v
if startup; then
    full='' coarse=''
    auto_turn
    first_key
    hold Left
    hold Up
    zoom_keys
    quit_key
else
    not_ok "turning, keys, zoom and q" "not checked: the viewer showed no picture"
fi

# ---- SIGTERM restores the terminal too ----------------------------------------------------------
start_viewer s
picture_up() { screen s | grep -q '▀'; }
if poll 10 picture_up; then
    kill -TERM "$(cat "$tmpdir/s.pid")"
    if poll 5 exited s; then
        why=$(restored s 143)
        if [ -z "$why" ]; then
            ok "SIGTERM restores the terminal (exit status 143)"
        else
            not_ok "SIGTERM restores the terminal" "$why"
        fi
    else
        not_ok "SIGTERM restores the terminal" "the viewer still runs 5 s after SIGTERM"
    fi
else
    not_ok "SIGTERM restores the terminal" "the viewer showed no picture"
fi

# ---- stdin not a terminal: one error line, status 2 ------------------------------------------------
tm new-session -d -s n -x 100 -y 10 \
    "$(printf '%q' "$viewer") </dev/null 2>$tmpdir/err; echo \$? >$tmpdir/rc"
rc_written() { [ -s "$tmpdir/rc" ]; }
if poll 10 rc_written; then
    rc=$(cat "$tmpdir/rc")
    lines=$(wc -l <"$tmpdir/err")
    if [ "$rc" = 2 ] && [ "$lines" = 1 ]; then
        ok "stdin not a terminal: one error line, exit status 2"
    else
        not_ok "stdin not a terminal: one error line, exit status 2" \
            "status $rc, $lines lines: $(head -c 200 "$tmpdir/err")"
    fi
else
    not_ok "stdin not a terminal: one error line, exit status 2" "the viewer did not exit within 10 s"
fi

exit "$failed"
