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
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then sudo_cmd=(sudo); fi
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
