#!/usr/bin/env bash
# ThreadSanitizer stage: builds only the C API, the libraries it links and its thread test
# with -fsanitize=thread, and runs the test (two threads with distinct handles at once:
# bodies, patterns, meshes, simulators; the per-thread errors and the error function).
# Called by scripts/test.sh; alone: scripts/test_tsan.sh [BUILD_DIR] (default build-tsan).
# -O1 keeps the instrumented build quick; apps, benchmarks and the shared library are off.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build-tsan}"
jobs="$(nproc)"
start=$(date +%s)
echo "== ThreadSanitizer: the C API thread test"
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS_RELEASE="-O1 -g1" \
  -DCMAKE_CXX_FLAGS_RELEASE="-O1 -g1" -DCMAKE_C_FLAGS="-fsanitize=thread" -DCMAKE_CXX_FLAGS="-fsanitize=thread" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread" -DDRAPE_BUILD_APPS=OFF -DDRAPE_BUILD_BENCH=OFF \
  -DDRAPE_BUILD_CAPI_SHARED=OFF -DDRAPE_SERIAL_LOOPS=ON >/dev/null
cmake --build "$build" -j"$jobs" --target drape_capi_thread_test
# halt_on_error: the first race fails the stage (exit code 66), with both stacks printed.
# OMP_NUM_THREADS=1: libcloth's OpenMP loops then run on the calling thread; the OpenMP
# runtime is not instrumented, so its own barriers would be invisible to TSan. The test is
# about the C API's threads (distinct handles at once), not about OpenMP's.
(cd "$build" && OMP_NUM_THREADS=1 TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 ${TSAN_OPTIONS:-}" \
   ctest --output-on-failure --timeout 900 -R "^capi: two threads, distinct handles$")
echo "== ThreadSanitizer stage: $(( $(date +%s) - start )) s"
