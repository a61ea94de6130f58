#!/usr/bin/env bash
# Runs Drape's libFuzzer harnesses (fuzz/, docs/hardening.md).
#
#   scripts/fuzz.sh [SECONDS] [NAME...]        fuzz each NAME (default: all) for SECONDS (default 60)
#   scripts/fuzz.sh --regress [SECONDS] [NAME...]
#       replay every kept crash of fuzz/regressions/NAME/ (each must now pass), then fuzz
#       for SECONDS (default 20; 0 = replay only): the short stage of scripts/test.sh.
#
# Builds only the harnesses asked for (and the libraries they link) with clang,
# -fsanitize=fuzzer,address,undefined in $DRAPE_FUZZ_BUILD (default build-fuzz/). Seeds come
# from fuzz/corpus/NAME/ (read only); inputs that reach new coverage go to
# $DRAPE_FUZZ_BUILD/corpus/NAME/, crashes to $DRAPE_FUZZ_BUILD/artifacts/NAME/. Prints per
# harness the executions, libFuzzer's coverage (cov: edges, ft: features), corpus size,
# time and the result; exits 1 if any harness crashed, leaked or hung.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${DRAPE_FUZZ_BUILD:-$here/build-fuzz}"
regress=0
if [ "${1:-}" = "--regress" ]; then regress=1; shift; fi
seconds=60
((regress)) && seconds=20
if [[ "${1:-}" =~ ^[0-9]+$ ]]; then seconds="$1"; shift; fi
names=("$@")
if ((${#names[@]} == 0)); then
  for d in "$here"/fuzz/corpus/*/; do names+=("$(basename "$d")"); done
fi

if [ ! -f "$build/CMakeCache.txt" ]; then
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  CC=clang CXX=clang++ cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 \
    -DDRAPE_FUZZ=ON -DDRAPE_BUILD_TESTS=OFF -DDRAPE_BUILD_APPS=OFF -DDRAPE_BUILD_BENCH=OFF \
    -DDRAPE_WARNINGS_AS_ERRORS=OFF "${launcher[@]}" >/dev/null
fi
targets=()
for n in "${names[@]}"; do targets+=("fuzz_$n"); done
cmake --build "$build" -j"${DRAPE_FUZZ_JOBS:-$(nproc)}" --target "${targets[@]}" >/dev/null

# leak detection on; a UBSan report aborts (the harness flags make it fatal); the memory
# and time caps turn an unbounded allocation or a hang into a finding.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=1}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$here/scripts/lsan.supp}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
flags=(-rss_limit_mb=2560 -malloc_limit_mb=1024 -timeout=30 -print_final_stats=1 -close_fd_mask=1)

status=0
printf '%-18s %12s %8s %8s %8s %7s  %s\n' fuzzer executions cov ft corpus seconds result
for n in "${names[@]}"; do
  bin="$build/fuzz/fuzz_$n"
  work="$build/corpus/$n"; art="$build/artifacts/$n"
  mkdir -p "$work" "$art"
  result=ok
  if ((regress)) && [ -d "$here/fuzz/regressions/$n" ] && compgen -G "$here/fuzz/regressions/$n/*" >/dev/null; then
    if ! "$bin" "${flags[@]}" "$here"/fuzz/regressions/"$n"/* >"$art/replay.log" 2>&1; then
      result="REGRESSION (see $art/replay.log)"; status=1
    fi
  fi
  log="$art/fuzz.log"
  start=$(date +%s)
  : >"$log"
  # --regress 0: replay only (libFuzzer's -max_total_time=0 would mean "no limit").
  if ((seconds > 0)) && ! "$bin" "${flags[@]}" -max_total_time="$seconds" -artifact_prefix="$art/" "$work" "$here/fuzz/corpus/$n" >"$log" 2>&1; then
    result="CRASH (see $log)"; status=1
  fi
  elapsed=$(( $(date +%s) - start ))
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1 || true)
  line=$(grep -E '^#[0-9]+.*cov: ' "$log" | tail -1 || true)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$line"); ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$line")
  corp=$(sed -n 's/.* corp: \([0-9]*\).*/\1/p' <<<"$line")
  printf '%-18s %12s %8s %8s %8s %7s  %s\n' "$n" "${execs:-?}" "${cov:-?}" "${ft:-?}" "${corp:-?}" "$elapsed" "$result"
done
exit $status
