#!/usr/bin/env bash
# Builds the jaus-node Debian package: installs what the project needs,
# builds a Release tree (programs, libraries, man pages; no tests) and runs
# cpack. Prints the path of the .deb, e.g. build/package/jaus-node_0.1.0_amd64.deb;
# install it with: sudo apt install ./build/package/jaus-node_*.deb
# Usage: ./scripts/package.sh (from anywhere)
set -euo pipefail
cd "$(dirname "$0")/.."

./scripts/setup.sh

dir=build/package
# Prefix /usr at configure time too, so GNUInstallDirs picks Debian's
# multiarch libdir (lib/<triplet>) and /etc, as the package installs there.
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=/usr -DJAUS_BUILD_TESTS=OFF \
  -DJAUS_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$dir" -j "$(nproc)"
(cd "$dir" && cpack -G DEB >/dev/null)
deb=$(ls "$dir"/jaus-node_*.deb)
echo "== $deb"
dpkg-deb -f "$deb" Package Version Depends
