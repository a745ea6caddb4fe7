#!/usr/bin/env bash
# Quick start 1: install what is missing, build, and run the main job on the bundled samples.
# Until the planner lands (`feedplan plan`), the main job is: build the sample model database from
# virtual cutting tests (once; build/sample.db), show its models, generate the trochoid sample (seed 003
# Table 2) with its engagement profile (out/trochoid_engagement.csv), and run today's constant-feed
# trochoid program on the virtual machine (out/trochoid_force.csv, out/trochoid_force.svg).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh"
feedplan="$root/build/cli/feedplan"
if [[ ! -s "$root/build/sample.db" ]]; then
  echo "building the sample model database (virtual cutting tests; a few minutes, once)"
  bash "$root/scripts/build-sample-db.sh" "$root/build/sample.db"
fi
"$feedplan" db list
mkdir -p "$root/out"
"$feedplan" cycle "$root/samples/trochoid.yaml" --engagement "$root/out/trochoid_engagement.csv"
"$feedplan" simulate "$root/samples/trochoid_constant_feed.ngc" --spec "$root/samples/trochoid.yaml" \
    --log "$root/out/trochoid_force.csv" --plot "$root/out/trochoid_force.svg"
