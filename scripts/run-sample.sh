#!/usr/bin/env bash
# Quick start 1: install what is missing, build, and run the main job on the bundled sample database:
# plan the feeds of the trochoid sample (seed 003 Table 2) so the predicted cutting force holds 300 N,
# write the G-code (out/trochoid.nc), the plan report (out/trochoid_plan.json, out/trochoid_plan.csv)
# and its plot (out/trochoid_plan.svg), and run the program on the virtual machine to compare its
# per-revolution peak forces with the target. The sample model database (build/sample.db) is built
# from virtual cutting tests the first time (a few minutes).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh"
feedplan="$root/build/cli/feedplan"
if [[ ! -s "$root/build/sample.db" ]]; then
  echo "building the sample model database (virtual cutting tests; a few minutes, once)"
  bash "$root/scripts/build-sample-db.sh" "$root/build/sample.db"
fi
# A database built by an older feedplan is migrated in place (nothing in it is lost).
"$feedplan" db init --db "$root/build/sample.db" > /dev/null
mkdir -p "$root/out"
"$feedplan" plan "$root/samples/trochoid.yaml" --db "$root/build/sample.db" -o "$root/out/trochoid.nc" \
    --report "$root/out/trochoid_plan.json" --csv "$root/out/trochoid_plan.csv" --plot "$root/out/trochoid_plan.svg" \
    --simulate
