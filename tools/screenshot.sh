#!/usr/bin/env bash
# Render an .rrd with its default blueprint to a PNG using the headless Rerun viewer.
#
#   tools/screenshot.sh RECORDING.rrd OUT.png [FRAME] [WIDTHxHEIGHT]
#
# Without FRAME: `rerun RRD --headless --screenshot-to PNG` (time cursor at the first frame).
# With FRAME: a headless viewer is started on 127.0.0.1, the recording is opened, the time
# cursor is moved to FRAME on the `frame` timeline once everything has loaded, and the
# screenshot is taken then (rerun.experimental.ViewerClient).
#
# Needs a Vulkan driver; on Debian/Ubuntu: apt-get install -y mesa-vulkan-drivers (lavapipe,
# software rendering, no GPU needed). Uses the `rerun` of the project venv when present.
set -euo pipefail

if [[ $# -lt 2 ]]; then
    echo "usage: $0 RECORDING.rrd OUT.png [FRAME] [WIDTHxHEIGHT]" >&2
    exit 2
fi
rrd=$1
png=$2
frame=${3:-}
size=${4:-1600x900}
[[ -f "$rrd" ]] || { echo "error: $rrd: no such file" >&2; exit 2; }

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bin_dir=$here/.venv/bin
rerun_bin=${RERUN_BIN:-$bin_dir/rerun}
[[ -x "$rerun_bin" ]] || rerun_bin=$(command -v rerun) || { echo "error: rerun not found" >&2; exit 2; }
python_bin=$bin_dir/python
[[ -x "$python_bin" ]] || python_bin=$(command -v python3)

# The viewer wants a runtime dir; keep it private and throw it away afterwards.
runtime=$(mktemp -d)
viewer_pid=
cleanup() {
    [[ -n "$viewer_pid" ]] && kill "$viewer_pid" 2>/dev/null || true
    rm -rf "$runtime"
}
trap cleanup EXIT
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-$runtime}
# Usage analytics off: rerun 0.41 skips them when CI is set (there is no RERUN_ANALYTICS).
export CI=${CI:-1}
export RUST_LOG=${RUST_LOG:-error}
mkdir -p "$(dirname "$png")"
png_abs=$(cd "$(dirname "$png")" && pwd)/$(basename "$png")
rrd_abs=$(cd "$(dirname "$rrd")" && pwd)/$(basename "$rrd")

if [[ -z "$frame" ]]; then
    # The headless viewer may shoot before every chunk has streamed in (static map only); take
    # a few shots and keep the one with the most content, i.e. the largest PNG.
    best=0
    for attempt in 1 2 3; do
        shot="$runtime/shot$attempt.png"
        "$rerun_bin" "$rrd_abs" --headless --renderer vulkan --bind 127.0.0.1 --port auto \
            --screenshot-to "$shot" --window-size "$size" >&2 || continue
        bytes=$(stat -c %s "$shot" 2>/dev/null || echo 0)
        if ((bytes > best)); then
            best=$bytes
            cp "$shot" "$png_abs"
        fi
    done
    ((best > 0)) || { echo "error: no screenshot written to $png" >&2; exit 1; }
    echo "wrote $png"
    exit 0
fi

port=$("$python_bin" -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
# Start the viewer binary itself (not the Python wrapper script) so that its pid is the one to stop.
viewer_bin=$("$python_bin" -c 'import pathlib, rerun_cli; print(pathlib.Path(rerun_cli.__file__).parent / "rerun")' 2>/dev/null || echo "$rerun_bin")
"$viewer_bin" --headless --renderer vulkan --bind 127.0.0.1 --port "$port" \
    --window-size "$size" --hide-welcome-screen >/dev/null 2>&1 &
viewer_pid=$!
"$python_bin" - "$port" "$rrd_abs" "$frame" "$png_abs" <<'PY'
import sys
import time

from rerun.experimental import ViewerClient

port, rrd, frame, png = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
deadline = time.monotonic() + 30
while True:
    try:
        viewer = ViewerClient.connect(f"rerun+http://127.0.0.1:{port}/proxy")
        viewer.get_state()
        break
    except Exception:  # noqa: BLE001 - the viewer is still starting
        if time.monotonic() > deadline:
            raise
        time.sleep(0.3)
viewer.open(rrd)
while viewer.get_state().loading and time.monotonic() < deadline:
    time.sleep(0.3)
viewer.set_time("frame", sequence=frame, play_state="paused")
time.sleep(1.0)  # let the viewer repaint at the new time
viewer.save_screenshot(png)
PY
[[ -s "$png_abs" ]] || { echo "error: no screenshot written to $png" >&2; exit 1; }
echo "wrote $png"
