#!/usr/bin/env bash
# README command 1: install the packages, build, and run the built-in default scene
# (about 2,000 spheres deposited into a box) into ./upgrain-output. A second run skips
# every finished step, including the scene when its summary is already there.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/install-deps.sh"
"$here/scripts/build.sh" "$here/build" -DCMAKE_BUILD_TYPE=Release
out="${UPGRAIN_OUTPUT:-$PWD/upgrain-output}"
if [ -f "$out/summary.json" ]; then
  echo "run-default: $out/summary.json exists: the default scene has already run (remove $out to run it again)"
  cat "$out/summary.json"
  exit 0
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
"$here/build/coupling/upgrain" --output "$out"
