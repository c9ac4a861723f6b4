#!/usr/bin/env bash
# Configures and builds one build folder. Usage: scripts/build.sh <folder> [cmake options]
# Re-running it only rebuilds what changed (ninja, ccache).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$1"; shift
# ccache across build folders and checkouts: paths below the checkout are hashed relative to
# it, and the build folder's name is not hashed (deal.II's flags include -g).
export CCACHE_NOHASHDIR=1
export CCACHE_BASEDIR="$here"
if [ ! -f "$build/build.ninja" ]; then
  cmake -S "$here" -B "$build" -G Ninja "$@"
fi
cmake --build "$build" -j"${UPGRAIN_JOBS:-2}"
