#!/usr/bin/env bash
# Fuzzes the parameter-file reader and the checkpoint reader with libFuzzer under
# AddressSanitizer and UBSan (docs/input.md, "Fuzzing").
#   scripts/fuzz.sh [MINUTES] [TARGET...]     default: 10 minutes each, both targets
# Builds build-fuzz/ with clang (-DUPGRAIN_FUZZ=ON), then runs each target for MINUTES on one
# core, starting from its stored corpus (tests/fuzz/corpus/<target>/) and, for the scene
# reader, the example scenes and the bad-input cases. New interesting inputs go to
# build-fuzz/corpus/<target>/; every crash, hang or memory blow-up is written to
# build-fuzz/crashes/<target>/ and the run goes on; the script exits non-zero when any was
# found. Fix each, then copy its input into the stored corpus so that CI (ctest -L fuzz)
# replays it.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
minutes="${1:-10}"
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(scene_file_fuzzer checkpoint_fuzzer)
command -v clang++ >/dev/null || { echo "fuzz.sh: clang++ not found (scripts/install-deps.sh installs it)" >&2; exit 1; }

build="$here/build-fuzz"
CC=clang CXX=clang++ cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DUPGRAIN_FUZZ=ON \
  -DUPGRAIN_WERROR=ON >/dev/null
cmake --build "$build" -j"${UPGRAIN_JOBS:-2}" --target "${targets[@]}"

# allocator_may_return_null: a huge malloc returns null as glibc's does (HDF5 checks it); a
# huge `new` in Upgrain's code still throws std::bad_alloc, which the targets report.
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:allocator_may_return_null=1:suppressions=$here/tests/fuzz/hdf5.supp
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
for t in "${targets[@]}"; do
  work="$build/corpus/$t" crashes="$build/crashes/$t/"
  mkdir -p "$work" "$crashes"
  seeds=("$here/tests/fuzz/corpus/$t")
  if [ "$t" = scene_file_fuzzer ]; then
    seeds+=("$here/examples"/*/ "$here/tests/bad_input/cases" "$here/tests/end_to_end")
  fi
  echo "fuzz.sh: $t for $minutes min (corpus $work, crashes $crashes)"
  before=$(ls "$crashes" | wc -l)
  # -fork=1 with -ignore_*: the run goes on for its whole time after a finding, each written
  # to $crashes; -timeout: an input that takes longer than 10 s is a hang; -rss_limit_mb: one
  # that needs more than 2 GB, a memory blow-up.
  (cd "$crashes" && "$build/tests/fuzz/$t" -max_total_time=$((minutes * 60)) -fork=1 -ignore_crashes=1 \
    -ignore_ooms=1 -ignore_timeouts=1 -timeout=10 -rss_limit_mb=2048 -max_len=131072 -print_final_stats=1 \
    -artifact_prefix="$crashes" "$work" "${seeds[@]}") || true
  found=$(($(ls "$crashes" | wc -l) - before))
  echo "fuzz.sh: $t: $found new finding(s) in $crashes"
  [ "$found" -eq 0 ] || status=1
done
exit "${status:-0}"
