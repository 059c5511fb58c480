#!/usr/bin/env bash
# Installs the Debian packages the project builds with. Idempotent; needs root
# (or sudo). Nothing is downloaded at build time: everything comes from here.
# Usage: ./scripts/setup.sh            the packages to build and test
#        ./scripts/setup.sh --browser  the browser tests' Chromium (scripts/test.sh
#                                      installs it while the first build runs)
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  clang lld             # the sanitizer build and libFuzzer targets; lld links fast
  libboost-dev          # Asio, MSM, CRC (header-only parts)
  libyaml-cpp-dev       # configuration files
  libgeographiclib-dev  # WGS 84 <-> local frame of the simulated vehicle
  nlohmann-json3-dev    # JSON form of messages
  libpng-dev libjpeg62-turbo-dev  # the visual sensor's images (PNG, JPEG)
  libcli11-dev          # command-line parsing
  libspdlog-dev libfmt-dev
  libgtest-dev libgmock-dev
  libbenchmark-dev
  groff-base            # tests/package renders the generated man pages (groff -ww: no warning)
  lintian               # tests/package checks the jaus-node .deb with Debian's package checker
  tshark                # tests/wireshark runs the generated Wireshark dissector in tshark
  iproute2 nftables     # tests/network: network namespaces, a bridge, veths (ip) and packet loss (nft)
)
if [ "${1:-}" = "--browser" ]; then
  # tests/browser: jaus-console's page in headless Chromium (tests only;
  # 26 packages, 133 MB of .debs, about 30 s to fetch and install).
  packages=(chromium chromium-driver)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages already installed"
  exit 0
fi

echo "setup: installing ${missing[*]}"
sudo_cmd=""
[ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo_cmd apt-get update -qq
$sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
