#!/usr/bin/env bash
# Configures and builds one build folder.
# Usage: scripts/build.sh <folder> [cmake options] [--target T ...]
# Without --target it builds everything. Re-running it only rebuilds what changed (ninja,
# ccache); the folder is configured again only when the options differ from its last ones.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$1"; shift
options=(); targets=()
while [ $# -gt 0 ]; do
  if [ "$1" = "--target" ]; then targets+=("--target" "$2"); shift 2; else options+=("$1"); shift; fi
done
# ccache across build folders and checkouts: paths below the checkout are hashed relative to
# it, and the build folder's name is not hashed (deal.II's flags include -g).
export CCACHE_NOHASHDIR=1
export CCACHE_BASEDIR="$here"
stamp="$build/.upgrain-options"
if [ ! -f "$build/build.ninja" ] || [ "$(cat "$stamp" 2>/dev/null)" != "${options[*]-}" ]; then
  cmake -S "$here" -B "$build" -G Ninja ${options[@]+"${options[@]}"}
  printf '%s' "${options[*]-}" > "$stamp"
fi
cmake --build "$build" -j"${UPGRAIN_JOBS:-2}" ${targets[@]+"${targets[@]}"}
