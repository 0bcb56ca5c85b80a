#!/bin/sh
# Drives `clothsim view` in a real X window with real input (xdotool's XTEST events, as a
# user's mouse and keyboard make them) on an Xvfb server of its own, for
# tests/viewer/viewer_input_test.cpp. Each session pauses, resets to the rest state, acts, and
# quits with Ctrl+Q; the viewer writes its last frame (SESSION.png) and state (SESSION.csv).
#   drive_viewer.sh CLOTHSIM SCENE OUTDIR SESSION
# SESSION: step   three N presses (one frame's substeps each)
#          pin    Ctrl+click the cloth's middle, then four N presses
#          grab   press on the cloth, drag 60 px right and keep it held over four N presses
#          orbit  P (a screenshot into OUTDIR/out/), a 300 px left drag on empty space
# The window is 1280x800; its 3-D view lies right of the 360 px panel.
set -eu
exe=$1
scene=$2
out=$3
session=$4
mkdir -p "$out"
cd "$out"

# A display number of the server's own choosing (-displayfd): tests run side by side.
fifo="$out/display.$$"
rm -f "$fifo"
mkfifo "$fifo"
Xvfb -displayfd 3 -screen 0 1280x800x24 -nolisten tcp 3>"$fifo" 2>"$out/xvfb.log" &
xvfb=$!
read -r display <"$fifo"
rm -f "$fifo"
export DISPLAY=":$display"
viewer=
cleanup() {
    [ -n "$viewer" ] && kill "$viewer" 2>/dev/null || true
    kill "$xvfb" 2>/dev/null || true
}
trap cleanup EXIT

"$exe" view "$scene" --backend cpu --precision double --no-vsync \
    --screenshot "$out/$session.png" --out-csv "$out/$session.csv" 2>"$out/$session.log" &
viewer=$!
window=$(timeout 60 xdotool search --sync --onlyvisible --name '^clothsim$' | head -1)
[ -n "$window" ] || { echo "drive_viewer.sh: no clothsim window within 60 s" >&2; exit 1; }
xdotool windowfocus --sync "$window"
pause() { sleep 0.4; }
key() {
    xdotool key "$1"
    pause
}
at() { xdotool mousemove --window "$window" --sync "$1" "$2"; }

pause
key space  # pause
key r      # reset to the rest state (stays paused)
case "$session" in
step)
    key n
    key n
    key n
    ;;
pin)
    at 800 500
    xdotool keydown ctrl click 1 keyup ctrl
    pause
    for _ in 1 2 3 4; do key n; done
    ;;
grab)
    at 880 540
    xdotool mousedown 1
    pause
    at 910 540
    pause
    at 940 540
    pause
    for _ in 1 2 3 4; do key n; done
    ;;
orbit)
    key p  # the panel's screenshot: out/screenshot.png
    at 1240 100
    xdotool mousedown 1
    pause
    at 1090 100
    pause
    at 940 100
    pause
    xdotool mouseup 1
    pause
    ;;
*)
    echo "drive_viewer.sh: unknown session '$session'" >&2
    exit 2
    ;;
esac
xdotool key ctrl+q
# The viewer closes within a few frames; one that does not is killed and the session fails.
for _ in $(seq 100); do
    kill -0 "$viewer" 2>/dev/null || break
    sleep 0.2
done
if kill -0 "$viewer" 2>/dev/null; then
    echo "drive_viewer.sh: the viewer did not close on Ctrl+Q" >&2
    exit 1
fi
status=0
wait "$viewer" || status=$?
viewer=
xdotool mouseup 1 2>/dev/null || true
exit "$status"
