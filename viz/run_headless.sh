#!/usr/bin/env bash
# Runs a command that needs an X display (VTK rendering): directly when DISPLAY is set,
# otherwise under a virtual X server (xvfb-run -a picks a free display number, so parallel
# runs do not collide).
#   viz/run_headless.sh /usr/bin/python3 viz/render_vtu.py out/
set -euo pipefail
if [ $# -eq 0 ]; then
  echo "usage: $0 COMMAND [ARGS...]" >&2
  exit 2
fi
if [ -n "${DISPLAY:-}" ]; then
  exec "$@"
fi
if ! command -v xvfb-run >/dev/null 2>&1; then
  echo "run_headless: no DISPLAY and no xvfb-run (scripts/install-deps.sh installs xvfb)" >&2
  exit 1
fi
# 24-bit colour: the default 8-bit screen gives banded colour maps.
exec xvfb-run -a -s "-screen 0 1600x1200x24" "$@"
