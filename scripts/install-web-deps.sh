#!/usr/bin/env bash
# Installs the npm packages of the HTML reports — uPlot (embedded into every report at build time) and
# puppeteer-core (drives headless Chromium in tests/report) — exactly as report/web/package-lock.json pins
# them (`npm ci`). Does nothing when report/web/node_modules is newer than the lock file.
set -euo pipefail
web="$(cd "$(dirname "$0")/../report/web" && pwd)"
stamp="$web/node_modules/.package-lock.json"
if [[ -f $stamp && $stamp -nt $web/package-lock.json ]]; then
  echo "install-web-deps: $web/node_modules is up to date"
  exit 0
fi
command -v npm >/dev/null 2>&1 || { echo "install-web-deps: npm is missing: run scripts/install-deps.sh" >&2; exit 1; }
echo "install-web-deps: npm ci in $web"
(cd "$web" && npm ci --no-audit --no-fund --prefer-offline)
