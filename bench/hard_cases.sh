#!/usr/bin/env bash
# The hard cases at full size (docs/hard-cases.md): the same tests as `ctest -L hard`, with
# UPGRAIN_HARD_FULL=1, which sets the sizes the issue names (a 1,000-sphere bed held for 1e6
# steps, a 100-grain column held for 1e5, 300 needles and discs, a 1:10 bed of 3,000). Minutes
# each; never run in CI. Usage: bench/hard_cases.sh [build folder] [gtest filter]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
filter="${2:-HardColumn.*:HardBeds.*}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
UPGRAIN_HARD_FULL=1 "$build/tests/hard/hard_tests" --gtest_filter="$filter"
