#!/bin/sh
# ctest: `coulomb view SCENE --frames N --screenshot FILE` under a virtual X server. Exit 77 (the
# test's SKIP_RETURN_CODE) when xvfb-run is not installed (Debian package xvfb).
# Usage: view_under_xvfb.sh COULOMB SCENE SCREENSHOT
set -eu
if ! command -v xvfb-run >/dev/null 2>&1; then
  echo "SKIP: xvfb-run not found (apt-get install xvfb)"
  exit 77
fi
rm -f "$3"
xvfb-run -a -s "-screen 0 1024x768x24" "$1" view "$2" --frames 5 --width 480 --height 360 \
  --screenshot "$3"
# A PNG of the window's size: signature, then IHDR width and height (big-endian) at bytes 16..23.
test "$(od -An -c -j1 -N3 "$3" | tr -d ' ')" = "PNG"
size=$(od -An -tu1 -j16 -N8 "$3" | tr -s ' ')
echo "screenshot IHDR bytes:$size"
test "$size" = " 0 0 1 224 0 0 1 104"
