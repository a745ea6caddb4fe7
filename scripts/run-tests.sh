#!/usr/bin/env bash
# Quick start 2: install what is missing, build, and run every test.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh"
ctest --test-dir "$root/build" --output-on-failure -j "${JOBS:-2}"
# The readers of user files under libFuzzer with ASan/UBSan, a bounded time each (own build dir, clang).
bash "$root/tests/fuzz/run-fuzzers.sh"
