#!/usr/bin/env bash
# README command 2 (and what CI runs): install the packages, build, and run the whole
# test suite through CTest: a Release build with warnings as errors runs every test, an
# AddressSanitizer+UBSan build runs the unit tests, and a clang build of the fuzz targets
# replays their stored corpus. A second run rebuilds only what changed.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/install-deps.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
jobs="${UPGRAIN_JOBS:-2}"

# The folder and options of scripts/run-default.sh: after it, only the tests and benchmarks
# are compiled here.
"$here/scripts/build.sh" "$here/build" -DCMAKE_BUILD_TYPE=Release -DUPGRAIN_WERROR=ON
(cd "$here/build" && ctest --output-on-failure -j"$jobs")

# Sanitizers: the engine, its unit tests and its message paths on 3 ranks (label sanitize:
# ghosts, migration, load balance); deal.II parts are left out to keep the build short, and
# the driver's bad-input cases run in the Release build above. Line
# tables (-g1) are all a sanitizer's stack trace needs; full debug information doubles the
# compile time of the force loop's instantiations (336 s against 160 s for one of them).
"$here/scripts/build.sh" "$here/build-asan" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-g1 -DUPGRAIN_WERROR=ON \
  -DUPGRAIN_SANITIZE=ON -DUPGRAIN_WITH_DEALII=OFF -DUPGRAIN_BUILD_BENCH=OFF
(cd "$here/build-asan" && ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ctest --output-on-failure -j"$jobs" -L 'unit|sanitize')

# The fuzz targets over their stored corpus, every input once (docs/input.md, "Fuzzing"): a
# build of their own with clang, of the few sources the two readers need. scripts/fuzz.sh
# fuzzes them for minutes; CI only replays what was found.
if command -v clang++ >/dev/null; then
  CC=clang CXX=clang++ "$here/scripts/build.sh" "$here/build-fuzz" -DCMAKE_BUILD_TYPE=Release -DUPGRAIN_WERROR=ON \
    -DUPGRAIN_FUZZ=ON
  (cd "$here/build-fuzz" && ctest --output-on-failure -L fuzz)
else
  echo "test.sh: clang++ not found: the fuzz targets were not built (scripts/install-deps.sh installs clang)"
fi
