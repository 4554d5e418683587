#!/usr/bin/env bash
# Runs the whole test suite (installs dependencies and builds first if needed).
# --quick runs only the tests labelled unit and run (tests/CMakeLists.txt lists the labels):
# about 2 minutes on 2 cores instead of the whole suite's 13.
# Benchmarks are not tests and do not run here (see benchmarks/README.md).
set -uo pipefail
quick=false
case "$*" in
  "") ;;
  --quick) quick=true ;;
  *) echo "usage: scripts/test.sh [--quick]" >&2; exit 2 ;;
esac
cd "$(dirname "$0")/.."
./scripts/install_dependencies.sh || exit 1
./scripts/build.sh || exit 1
cd build
# MPI_Init loads hwloc, whose GL plugin probes the X displays :0 to :9 for GPUs; a test process
# that reaches an X server another test started dies when that server stops. No test needs it.
export HWLOC_COMPONENTS=-gl
if [ "$quick" = true ]; then
  # ctest -L also runs the fixture setups these tests need; they carry the same labels.
  ctest -j "$(nproc)" -L 'unit|run' --output-on-failure --timeout 600 | tee ctest-quick.log
  status=${PIPESTATUS[0]}
  docs_status=0
  logs="ctest-quick.log"
else
  # The docs test (every command of the docs, about 10 minutes) runs beside the rest from the start:
  # within one ctest run it would start only after the tests that others depend on, and end alone.
  ctest -L docs --output-on-failure > ctest-docs.log 2>&1 &
  docs_pid=$!
  ctest -j "$(nproc)" -LE docs --output-on-failure --timeout 600 | tee ctest.log
  status=${PIPESTATUS[0]}
  wait "$docs_pid"
  docs_status=$?
  cat ctest-docs.log
  logs="ctest.log ctest-docs.log"
fi
passed=0
failed=0
for log in $logs; do
  summary=$(grep -E "tests passed, [0-9]+ tests failed out of [0-9]+" "$log" | tail -1)
  if [ -z "$summary" ]; then
    echo "no ctest summary in build/$log" >&2
    failed=$((failed + 1))
    continue
  fi
  f=$(echo "$summary" | sed -E 's/.* ([0-9]+) tests failed out of ([0-9]+).*/\1/')
  t=$(echo "$summary" | sed -E 's/.* ([0-9]+) tests failed out of ([0-9]+).*/\2/')
  passed=$((passed + t - f))
  failed=$((failed + f))
done
echo "${passed} passed, ${failed} failed"
[ "$status" -eq 0 ] && [ "$docs_status" -eq 0 ] && [ "$failed" -eq 0 ]
