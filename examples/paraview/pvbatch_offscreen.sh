#!/bin/sh
# pvbatch ARGS under a private virtual X server: Debian's ParaView renders through X only (no EGL or
# OSMesa, so `pvbatch --force-offscreen-rendering` aborts without a display). Xvfb -displayfd
# writes the display's number once the server listens; the server is stopped when pvbatch exits.
# On this machine pvbatch failed to connect ("bad X server connection") to a running Xvfb in about
# half of the runs (XOpenDisplay from Python never failed), under `xvfb-run` as well; a run that
# fails that way is tried again, six times at most.
#   examples/paraview/pvbatch_offscreen.sh examples/paraview/render_bed.py OUTPUT_FOLDER [...]
tmp=$(mktemp -d)
Xvfb -displayfd 3 -screen 0 1024x768x24 -nolisten tcp 3>"$tmp/display" 2>"$tmp/log" &
xvfb=$!
trap 'kill $xvfb 2>/dev/null; wait $xvfb 2>/dev/null; rm -rf "$tmp"' EXIT
tries=0
while [ ! -s "$tmp/display" ]; do
  tries=$((tries + 1))
  if [ $tries -gt 200 ] || ! kill -0 $xvfb 2>/dev/null; then
    echo "pvbatch_offscreen.sh: Xvfb did not start:" >&2
    cat "$tmp/log" >&2
    exit 1
  fi
  sleep 0.1
done
for attempt in 1 2 3 4 5 6; do
  DISPLAY=":$(cat "$tmp/display")" pvbatch "$@" >"$tmp/out" 2>&1
  code=$?
  if [ $code -eq 0 ] || ! grep -q "bad X server connection" "$tmp/out"; then
    cat "$tmp/out"
    exit $code
  fi
  echo "pvbatch_offscreen.sh: attempt $attempt: pvbatch could not open the display" >&2
  sleep 1
done
cat "$tmp/out"
exit $code
