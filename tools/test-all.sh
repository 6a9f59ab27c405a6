#!/usr/bin/env bash
# test-all.sh: installs what is missing, builds, and runs the whole test suite with CTest
# (JUnit report in build/junit.xml). `tools/test-all.sh -LE slow` runs the quick subset;
# any arguments are passed to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
jobs=$(nproc 2>/dev/null || echo 2)
ctest --test-dir build --output-on-failure -j"$jobs" --output-junit junit.xml "$@"
