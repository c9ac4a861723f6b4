#!/usr/bin/env bash
# The hard cases at full size (docs/hard-cases.md): the same tests as `ctest -L hard`, with
# UPGRAIN_HARD_FULL=1, which sets the sizes the issue names (a 1,000-sphere bed held for 1e6
# steps, a 100-grain column held for 1e5, 300 needles and discs held 1e5 steps after rest, a
# 1:10 bed of 3,000 spheres, a 1:5 bed of 1,000 ellipsoids; the continuum's locking study on
# its finer mesh). Minutes each; never run in CI. Usage: bench/hard_cases.sh [build folder] [gtest filter]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
filter="${2:-HardColumn.*:HardBeds.*}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
UPGRAIN_HARD_FULL=1 "$build/tests/hard/hard_tests" --gtest_filter="$filter"
# The continuum's locking study at its full mesh (Q3 reference on 47,775 dofs; 2 min), when
# the build has deal.II and the filter asks for it (HardContinuum.*).
fem="$build/tests/hard/hard_fem_tests"
if [ -x "$fem" ] && [[ "$filter" == *HardContinuum* ]]; then
  UPGRAIN_HARD_FULL=1 "$fem" --gtest_filter='HardContinuum.OpenSided*'
fi
