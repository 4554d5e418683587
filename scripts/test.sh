#!/usr/bin/env bash
# Runs the whole test suite (installs dependencies and builds first if needed).
# Benchmarks are not tests and do not run here (see benchmarks/README.md).
set -uo pipefail
cd "$(dirname "$0")/.."
./scripts/install_dependencies.sh || exit 1
./scripts/build.sh || exit 1
cd build
ctest -j "$(nproc)" --output-on-failure --timeout 600 | tee ctest.log
status=${PIPESTATUS[0]}
summary=$(grep -E "tests passed, [0-9]+ tests failed out of [0-9]+" ctest.log | tail -1)
failed=$(echo "$summary" | sed -E 's/.* ([0-9]+) tests failed out of ([0-9]+).*/\1/')
total=$(echo "$summary" | sed -E 's/.* ([0-9]+) tests failed out of ([0-9]+).*/\2/')
echo "$((total - failed)) passed, ${failed} failed"
exit "$status"
