#!/usr/bin/env bash
# The installed library works for another project: install feedplan to a temporary prefix, build the
# consumer project in tests/install/consumer against it with find_package(feedplan), and run it on the
# trochoid sample. Its plan (status, blocks, cycle time) must equal what the feedplan command plans from
# the same model.
#
# Usage: install_consumer_check.sh SOURCE_DIR BUILD_DIR FEEDPLAN_BIN
set -euo pipefail
src=$1 build=$2 feedplan=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
models="$src/tests/data/cli/s50c_d10_model.json"
spec="$src/samples/trochoid.yaml"

cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
cmake -S "$src/tests/install/consumer" -B "$work/consumer" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/configure.log" 2>&1 || { cat "$work/configure.log"; exit 1; }
cmake --build "$work/consumer" -j "${JOBS:-2}" > "$work/build.log" 2>&1 || { cat "$work/build.log"; exit 1; }

consumer=$("$work/consumer/plan_cycle" "$spec" "$models" "$work")
echo "consumer of the installed library:"
echo "$consumer"

"$feedplan" db import "$models" --db "$work/cli.db" > /dev/null
# The consumer plans with the library's defaults (blocks that write every ramp out): --feed-step 0 is that.
cli=$("$feedplan" plan "$spec" --db "$work/cli.db" -o "$work/trochoid.nc" --feed-step 0 --json)
# Top-level members of the pretty-printed JSON stand two spaces in.
expected=$(printf '%s\n' "$cli" | awk -F'[:,]' '
  /^  "status"/ { gsub(/[ "]/, "", $2); status = $2 }
  /^  "blocks"/ { gsub(/ /, "", $2); blocks = $2 }
  /^  "cycle_time_s"/ { time = $2 }
  END { printf "status: %s\nblocks: %s\ncycle time: %.2f s\n", status, blocks, time }')
echo "feedplan plan:"
echo "$expected"
[[ $consumer == "$expected" ]] || { echo "the consumer's plan differs from feedplan plan's"; exit 1; }
