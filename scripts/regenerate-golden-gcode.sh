#!/usr/bin/env bash
# Regenerates the G-code writer's golden files, tests/data/gcode/golden/<case>_<dialect>.nc, from the
# writer as it is now. Run it only when a change to the writer's output is intended, then review
# the diff: the golden files are how such changes are seen (tests/gcode/writer_golden_test.cpp).
#
# Usage: scripts/regenerate-golden-gcode.sh [BUILD_DIR]   (default: build; it must be configured,
# e.g. by scripts/build.sh)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-"$root/build"}
golden="$root/tests/data/gcode/golden"

cmake --build "$build" --target gcode_tests -j "${JOBS:-1}"
rm -f "$golden"/*.nc  # cases that no longer exist must not leave files behind
FEEDPLAN_REGENERATE_GOLDEN=1 "$build/tests/gcode/gcode_tests" \
    --gtest_filter='WriterGolden.OutputMatchesTheGoldenFilesByteForByte' --gtest_brief=1
"$build/tests/gcode/gcode_tests" --gtest_filter='WriterGolden*' --gtest_brief=1
git -C "$root" status --short -- tests/data/gcode/golden
echo "Review the changes with: git diff -- tests/data/gcode/golden"
