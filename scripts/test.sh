#!/usr/bin/env bash
# Installs what the project needs, builds it and runs every test:
#   1. Release build (-O3, -Wall -Wextra -Werror): libraries, apps, benchmarks, and the suites on
#      real sockets, processes and clocks (system, transport, host, OCU, conformance, Clearpath link);
#   2. Debug build with AddressSanitizer + UndefinedBehaviorSanitizer (-Werror): every suite, the
#      deterministic unit suites included (they run once, where the sanitizers watch them; line
#      tables only (-g1): all a sanitizer report needs, and a third less to compile);
#   3. libFuzzer targets (clang, -O1), each run briefly on its seed corpus.
# Usage: ./scripts/test.sh        (from anywhere; builds go to build/)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

./scripts/setup.sh

jobs=$(nproc)
run_suite() {  # $1 build dir, remaining args: cmake options
  local dir=$1; shift
  local start=$SECONDS
  cmake -S "$root" -B "$dir" -G Ninja "$@" >/dev/null
  cmake --build "$dir" -j "$jobs"
  local built=$SECONDS
  ctest --test-dir "$dir" --output-on-failure -j "$jobs" --timeout 300
  echo "== $dir: built in $((built - start)) s, tested in $((SECONDS - built)) s"
}

echo "== release build and tests"
run_suite build/release -DCMAKE_BUILD_TYPE=Release -DJAUS_BUILD_UNIT_TESTS=OFF

echo "== debug build with address + undefined-behaviour sanitizers, tests"
run_suite build/asan -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-g1 -DJAUS_SANITIZE=ON -DJAUS_BUILD_BENCHMARKS=OFF

if command -v clang++ >/dev/null; then
  echo "== fuzz targets (libFuzzer, short smoke run)"
  CXX=clang++ cmake -S "$root" -B build/fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
    -DJAUS_BUILD_FUZZERS=ON -DJAUS_BUILD_TESTS=OFF -DJAUS_BUILD_BENCHMARKS=OFF >/dev/null
  cmake --build build/fuzz -j "$jobs" --target fuzz_targets
  # Each target runs 20 s on its seed corpus, as many at once as there are cores.
  fuzz_one() {  # $1 target; its output goes to build/fuzz/<name>.log
    local target=$1 name corpus status=0
    name=$(basename "$target")
    corpus=$(mktemp -d)
    cp -r "$root/tests/fuzz/corpus/$name/." "$corpus/" 2>/dev/null || true
    if [ "$name" = fuzz_jaus_decode ] || [ "$name" = fuzz_node_receive ]; then
      # Seed with every JAUS vector, one file each.
      grep -hv '^#' "$root"/tests/data/jaus-openjaus*-vectors.txt | awk '{print $NF}' |
        while read -r hex; do printf '%s' "$hex" | perl -ne 'print pack("H*", $_)' > "$corpus/$(printf '%s' "$hex" | md5sum | cut -c1-16)"; done
    fi
    "$target" "$corpus" -max_total_time=20 -print_final_stats=0 -artifact_prefix="$root/build/fuzz/" \
      > "$root/build/fuzz/$name.log" 2>&1 || status=$?
    rm -rf "$corpus"
    return $status
  }
  targets=()
  for target in build/fuzz/fuzz/fuzz_*; do if [ -x "$target" ]; then targets+=("$target"); fi; done
  for ((i = 0; i < ${#targets[@]}; i += jobs)); do
    pids=()
    batch=("${targets[@]:i:jobs}")
    for target in "${batch[@]}"; do fuzz_one "$target" & pids+=($!); done
    for k in "${!batch[@]}"; do
      name=$(basename "${batch[$k]}")
      if ! wait "${pids[$k]}"; then
        echo "== $name failed:"; tail -n 40 "build/fuzz/$name.log"; exit 1
      fi
      echo "$name: $(grep -E '^Done [0-9]+ runs' "build/fuzz/$name.log" | tail -n 1)"
    done
  done
else
  echo "== clang not found: fuzz targets skipped"
fi
echo "== all tests passed in $SECONDS s"
