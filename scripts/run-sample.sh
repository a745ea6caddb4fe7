#!/usr/bin/env bash
# Quick start 1: install what is missing, build, and run the main job on the bundled samples.
# For now the main job generates the trochoid sample (seed 003 Table 2) and writes its engagement
# profile to out/trochoid_engagement.csv with a summary on stdout.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh"
mkdir -p "$root/out"
"$root/build/cli/feedplan" cycle "$root/samples/trochoid.yaml" --engagement "$root/out/trochoid_engagement.csv"
