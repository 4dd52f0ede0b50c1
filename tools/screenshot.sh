#!/usr/bin/env bash
# Render an .rrd with its blueprint to a PNG using the headless Rerun viewer.
#
#   tools/screenshot.sh RECORDING.rrd OUT.png [FRAME] [WIDTHxHEIGHT]
#
# A headless viewer is started on 127.0.0.1, the recording is opened, the time cursor is moved
# to FRAME on the `frame` timeline (if given) once everything has loaded, and the screenshot is
# taken then: workbench/viewer/screenshot.py, the same code that renders export thumbnails.
#
# Needs a Vulkan driver; on Debian/Ubuntu: apt-get install -y mesa-vulkan-drivers (lavapipe,
# software rendering, no GPU needed). Uses the python of the project venv when present.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
python_bin=$here/.venv/bin/python
[[ -x "$python_bin" ]] || python_bin=$(command -v python3)
export PYTHONPATH="$here${PYTHONPATH:+:$PYTHONPATH}"
exec "$python_bin" -m workbench.viewer.screenshot "$@"
