#!/usr/bin/env bash
# Fuzzes every reader of a user file with libFuzzer (fuzz/): builds the targets with clang in
# build-fuzz/, then runs each for MINUTES minutes (default 3), one after the other, seeded from the
# scenarios, the malformed-scenario corpus and tests/data/fuzz_seeds/<target>/.
#   scripts/fuzz.sh [MINUTES] [TARGET ...]
# A finding (crash, sanitizer report, hang over 10 s, leak) stops that target and leaves its input in
# build-fuzz/findings/<target>/; once fixed, copy it to tests/data/fuzz_regressions/<target>/, where
# tests/fuzz_regressions_test.cpp feeds it through the same reader in every test run.
# Needs clang-14 and libclang-rt-14-dev (libFuzzer), installed here when missing: the normal build
# and tests need neither.
set -euo pipefail
cd "$(dirname "$0")/.."
minutes=${1:-3}
shift || true
targets=("$@")
((${#targets[@]})) || targets=(fuzz_scenario_toml fuzz_scenario_frequencies fuzz_series_csv fuzz_events_csv fuzz_runs_jsonl)

scripts/install-deps.sh
IMPACTBENCH_EXTRA_PACKAGES="clang-14 libclang-rt-14-dev" scripts/install-deps.sh --only-extra

cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 \
      -DIMPACTBENCH_FUZZ=ON -DIMPACTBENCH_TESTS=OFF -DIMPACTBENCH_BENCH=OFF >/dev/null
cmake --build build-fuzz -j "$(nproc)" --target "${targets[@]}"

export ASAN_OPTIONS="abort_on_error=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
export TMPDIR=/dev/shm   # fuzz_runs_jsonl writes its folder there
status=0
for target in "${targets[@]}"; do
  corpus=build-fuzz/corpus/$target findings=build-fuzz/findings/$target
  mkdir -p "$corpus" "$findings"
  seeds=()
  for s in tests/data/fuzz_seeds/$target tests/data/fuzz_regressions/$target; do [[ -d $s ]] && seeds+=("$s"); done
  if [[ $target == fuzz_scenario_* ]]; then
    seeds+=(tests/data/malformed_scenarios scenarios/paper tests/data/report_suite)
  fi
  echo "fuzz: $target for $minutes min (seeds: ${seeds[*]:-none})"
  if ! "build-fuzz/fuzz/$target" "$corpus" "${seeds[@]}" -max_total_time=$((minutes * 60)) -timeout=10 \
       -rss_limit_mb=2048 -max_len=65536 -artifact_prefix="$findings/" -print_final_stats=1 2>"build-fuzz/$target.log"; then
    echo "fuzz: $target found a problem: build-fuzz/$target.log, input in $findings/" >&2
    status=1
  fi
  grep -E "^(stat::number_of_executed_units|stat::peak_rss_mb|#[0-9]+ *DONE)" "build-fuzz/$target.log" || true
done
exit $status
