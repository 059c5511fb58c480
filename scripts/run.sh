#!/usr/bin/env bash
# Installs what the project needs, builds the node daemon (and jausctl,
# jaus-console and jaus-conform, to talk to it, drive it and test it) and runs it with
# the default configuration (config/jausd.yaml: no hardware needed; listens
# for JAUS on UDP 0.0.0.0:3794). Stop it with Ctrl-C: every component shuts
# down and the platform is commanded to stop.
# Usage: ./scripts/run.sh [jausd options...]   e.g. --bind 127.0.0.1 --log-level debug
set -euo pipefail
cd "$(dirname "$0")/.."

./scripts/setup.sh

cmake -S . -B build/run -G Ninja -DCMAKE_BUILD_TYPE=Release -DJAUS_BUILD_TESTS=OFF -DJAUS_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build/run -j "$(nproc)" --target jausd jausctl jaus-console jaus-conform
echo "== jausd running (jausctl is build/run/apps/jausctl/jausctl, the browser console build/run/apps/jaus_console/jaus-console, jaus-conform build/run/apps/jaus_conform/jaus-conform; Ctrl-C stops)"
exec build/run/apps/jausd/jausd --config config/jausd.yaml --pid-file build/run/jausd.pid "$@"
