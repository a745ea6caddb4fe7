#!/usr/bin/env bash
# Makes the sample reports with the feedplan binary — a plan (trochoid) with its CSV, the same plan redrawn
# from its JSON report, the plan learned from one part cut on the virtual machine (learn --html: measured
# per-revolution peaks), a learning history of three cycles (loop --html) and a
# comparison — and opens them in headless Chromium (report_browser_test.mjs). The reports
# and the screenshots stay in OUT_DIR (screenshots/) as the test's artefacts.
#
# Usage: run_browser_test.sh FEEDPLAN SAMPLES_DIR TEST_DATA_DIR WEB_DIR CHROMIUM OUT_DIR
set -euo pipefail
feedplan=$1 samples=$2 data=$3 web=$4 chromium=$5 out=$6
here=$(cd "$(dirname "$0")" && pwd)
[[ -x $chromium ]] || { echo "Chromium is missing ($chromium): run scripts/install-deps.sh"; exit 1; }
[[ -d $web/node_modules/puppeteer-core ]] || { echo "puppeteer-core is missing in $web: run scripts/install-web-deps.sh"; exit 1; }
rm -rf "$out"
mkdir -p "$out"
db=$out/t.db
"$feedplan" db init --db "$db" > /dev/null
"$feedplan" db import "$data/cli/s50c_d10_model.json" --db "$db" > /dev/null
"$feedplan" plan "$samples/trochoid.yaml" --db "$db" -o "$out/plan.nc" --report "$out/plan.json" --csv "$out/plan.csv" \
  --html "$out/plan.html" > "$out/plan.txt"
"$feedplan" report "$out/plan.json" -o "$out/report.html" --db "$db"
"$feedplan" simulate "$out/plan.nc" --spec "$samples/trochoid.yaml" --material S50C --log "$out/part1.csv" > /dev/null 2>&1
"$feedplan" learn "$out/plan.json" "$out/part1.csv" -o "$out/next.nc" --db "$db" --report "$out/next.json" \
  --html "$out/learn.html" > "$out/learn.txt" 2>&1
"$feedplan" loop "$samples/corner.yaml" --db "$db" --cycles 3 --html "$out/history.html" > "$out/loop.txt"
"$feedplan" report "$data/report/compare.json" -o "$out/compare.html"
ls -l "$out"/*.html
node "$here/report_browser_test.mjs" --web-dir "$web" --chromium "$chromium" --shots "$out/screenshots" \
  --plan "$out/plan.html" --csv "$out/plan.csv" --report "$out/report.html" --history "$out/history.html" --cycles 3 \
  --learn "$out/learn.html" --learn-cycles 1 \
  --comparison "$out/compare.html" --compare-json "$data/report/compare.json"
