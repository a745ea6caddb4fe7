#!/usr/bin/env bash
# Configures and builds feedplan in ./build (Release, 2 parallel jobs unless JOBS is set).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release "$@" > "$root/build.log.tmp" 2>&1 || { cat "$root/build.log.tmp"; rm -f "$root/build.log.tmp"; exit 1; }
rm -f "$root/build.log.tmp"
cmake --build "$root/build" -j "${JOBS:-2}"
