#!/usr/bin/env bash
# README command 1: install the packages, build, and run the built-in default study
# (about 2,000 spheres deposited into a box, grid stress, the continuum column, report)
# into ./upgrain-output. A second run skips every finished step, including the study when
# its report is already there.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/install-deps.sh"
# Only the driver: the tests and benchmarks are built by scripts/test.sh, into the same
# folder with the same options, so that the second command compiles nothing twice.
"$here/scripts/build.sh" "$here/build" -DCMAKE_BUILD_TYPE=Release -DUPGRAIN_WERROR=ON --target upgrain
out="${UPGRAIN_OUTPUT:-$PWD/upgrain-output}"
if [ -f "$out/report.md" ]; then
  echo "run-default: $out/report.md exists: the default study has already run (remove $out to run it again)"
  exit 0
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
"$here/build/coupling/upgrain" --output "$out"
