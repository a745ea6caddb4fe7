#!/usr/bin/env bash
# Installs the Debian 12 packages feedplan needs to build, test and run. Idempotent: when every
# package is already present it installs nothing and does not touch apt's index.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libeigen3-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libceres-dev libsqlite3-dev
  libpq-dev postgresql  # libpq: the shared model database on a PostgreSQL server; the server: its tests start one
  libcli11-dev libyaml-cpp-dev nlohmann-json3-dev libfmt-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  linuxcnc-uspace  # rs274, LinuxCNC's interpreter: the oracle of the G-code tests (docs/method.md §7)
  clang libclang-rt-14-dev llvm  # libFuzzer, the ASan/UBSan runtimes, llvm-symbolizer (readable stacks): tests/fuzz/run-fuzzers.sh
  nodejs chromium  # the HTML reports: uPlot from npm embedded at build time, the headless-browser test (tests/report)
)
# npm: Debian's package, unless the node installed already brings its own (NodeSource's does).
if ! command -v npm >/dev/null 2>&1; then packages+=(npm); fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
else
  echo "install-deps: installing ${missing[*]}"
  sudo_cmd=()
  if [[ $(id -u) -ne 0 ]]; then sudo_cmd=(sudo); fi
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The npm packages of the HTML reports (uPlot, puppeteer-core), exactly as report/web/package-lock.json pins
# them; again only when node_modules is missing or older than the lock file.
"$(dirname "$0")/install-web-deps.sh"
