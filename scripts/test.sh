#!/usr/bin/env bash
# Installs what the project needs, builds it and runs every test:
#   1. Release build (GCC, -O2 as Debian builds, -Wall -Wextra -Werror): libraries, apps, the codec's speed guard,
#      the system suite, which runs the shipped programs end to end, the network suite (nodes in
#      network namespaces under packet loss: needs root), the browser suite (jaus-console's page in
#      headless Chromium, installed meanwhile) and the load suite (a node under a million datagrams;
#      the sanitizer tree floods it with a tenth of that);
#   2. Debug build with AddressSanitizer + UndefinedBehaviorSanitizer (clang, -Werror): every suite,
#      and the libFuzzer targets (libraries instrumented for coverage), each run briefly on its seed
#      corpus while the sanitizer suites run; line tables only (-g1), all a sanitizer report needs;
#      the libraries shared (the Release tree links them statically, as it ships).
#      Without clang the sanitizer build uses GCC and the fuzz targets are skipped.
# Two compilers, two sets of warnings. The Release system, network, browser and load suites
# (real-clock tests that mostly wait on sockets and timers, and one flood) run while the sanitizer
# tree compiles at a lower CPU priority, and the fuzz smoke at the lowest priority while the
# sanitizer suites run: the tests get the CPU whenever they need it, the rest takes what is left.
# The deterministic suites run as a few processes each (shards, not a process per test) below
# the real-clock tests' priority, beside them (cmake/jaus_tests.cmake).
# Usage: ./scripts/test.sh (from anywhere; builds go to build/)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

./scripts/setup.sh
# Chromium (the browser tests only) installs while the release tree compiles.
mkdir -p build
./scripts/setup.sh --browser > build/setup-browser.log 2>&1 &
browser_setup=$!

jobs=$(nproc)
configure_and_build() {  # $1 build dir, remaining args: cmake options; BUILD_NICENESS lowers the compiler's priority
  local dir=$1; shift
  local start=$SECONDS
  # Explicit returns: this also runs on the left of ||, where set -e does not apply.
  cmake -S "$root" -B "$dir" -G Ninja "$@" >/dev/null || return 1
  nice -n "${BUILD_NICENESS:-0}" cmake --build "$dir" -j "$jobs" || return 1
  echo "== $dir: built in $((SECONDS - start)) s"
}
run_tests() {  # $1 build dir, remaining args: more ctest options
  local dir=$1 start=$SECONDS; shift
  # A failing shard's output is long: keep its start and its end (gtest's list of failed tests).
  ctest --test-dir "$dir" --output-on-failure -j "$jobs" --timeout 300 --test-output-truncation middle "$@" || return 1
  echo "== $dir: tested in $((SECONDS - start)) s"
}
# The sanitizer suites (cmake/jaus_tests.cmake): the real-clock tests (label
# realtime: one process a test, or shards on sockets) hold a `realtime` slot
# each, one more slot than there are cores: all but the flood mostly wait on
# sockets and timers, so at normal priority they still ask for less CPU than
# there is. The deterministic shards (label deterministic, nice 10) take as
# many more jobs as there are cores and the CPU the real-clock tests leave.
run_sanitizer_tests() {  # $1 build dir
  local spec=$root/$1/realtime-slots.json  # absolute: ctest reads it from inside the tree
  local realtime_slots=$((jobs + 1))
  printf '{"version": {"major": 1, "minor": 0}, "local": [{"realtime": [{"id": "cores", "slots": %d}]}]}\n' \
    "$realtime_slots" > "$spec"
  run_tests "$1" -j $((realtime_slots + jobs)) --resource-spec-file "$spec"
}

echo "== release build"
# The benchmark programs are not built here (about 170 CPU s, a tenth of the
# tree; `ninja -C build/release benchmarks` builds them), but for
# codec_speed_guard, which the suites run.
configure_and_build build/release -DCMAKE_BUILD_TYPE=Release -DJAUS_TEST_SUITES=system -DJAUS_BENCHMARKS_IN_ALL=OFF

if ! wait "$browser_setup"; then echo "== installing Chromium failed:"; cat build/setup-browser.log; exit 1; fi
echo "== release system, network, browser and load suites (in the background, output at the end of the sanitizer build)"
release_log=build/release/system-suite.log
run_tests build/release > "$release_log" 2>&1 &
release_tests=$!
finish_release_tests() {
  local status=0
  wait "$release_tests" || status=$?
  echo "== release system, network, browser and load suites:"
  cat "$release_log"
  if [ "$status" -ne 0 ]; then echo "== release system, network, browser and load suites failed"; exit 1; fi
}

# The unity builds batch their files in the other order than the Release tree's
# (cmake/unity_order.cmake): a file missing an include that an earlier file of
# its batch made in one tree comes before that file, or in another batch, in
# the other, and fails there.
# The libraries are shared in this tree: linked statically, each of its fifty
# test, fuzz and program executables carried a copy of every instrumented
# library (230-290 MB each, 11 GB for the tree, which once filled CI's disk).
# Shared, the tree is 3.5 GB; its links take 45 CPU s instead of 170, and its
# tests run about 15 % slower (position-independent code): in CI the build is
# about 25 s shorter and the suites about 25 s longer. The Release tree, which
# is what ships, stays static.
sanitizer_options=(-DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-g1 -DJAUS_SANITIZE=ON -DJAUS_BUILD_BENCHMARKS=OFF
                   -DJAUS_UNITY_BUILD_REVERSED=ON -DBUILD_SHARED_LIBS=ON)
if command -v clang++ >/dev/null; then
  echo "== debug build with address + undefined-behaviour sanitizers (clang), every suite, fuzz targets"
  export CXX=clang++
  sanitizer_options+=(-DJAUS_BUILD_FUZZERS=ON)
else
  echo "== debug build with address + undefined-behaviour sanitizers (gcc), every suite"
fi
asan_built=0
BUILD_NICENESS=10 configure_and_build build/asan "${sanitizer_options[@]}" && asan_built=1
finish_release_tests
if [ "$asan_built" != 1 ]; then echo "== sanitizer build failed"; exit 1; fi
fuzz_dir=build/asan/fuzz
fuzz_log=build/asan/fuzz-smoke.log
# Each fuzz target runs 20 s on its seed corpus, as many at once as there are
# cores, at the lowest priority while the sanitizer suites run: the tests,
# many of which wait on sockets and timers, get the CPU whenever they need it
# and the fuzzers take the rest (a target given less CPU makes fewer runs in
# its 20 s; it still runs every seed and then mutates).
fuzz_one() {  # $1 target; its output goes to $fuzz_dir/<name>.log
  local target=$1 name corpus status=0
  name=$(basename "$target")
  corpus=$(mktemp -d)
  cp -r "$root/tests/fuzz/corpus/$name/." "$corpus/" 2>/dev/null || true
  if [ "$name" = fuzz_jaus_decode ] || [ "$name" = fuzz_node_receive ]; then
    # Seed with every JAUS vector, one file each.
    grep -hv '^#' "$root"/tests/data/jaus-openjaus*-vectors.txt | awk '{print $NF}' |
      while read -r hex; do printf '%s' "$hex" | perl -ne 'print pack("H*", $_)' > "$corpus/$(printf '%s' "$hex" | md5sum | cut -c1-16)"; done
  fi
  nice -n 19 "$target" "$corpus" -max_total_time=20 -print_final_stats=0 -artifact_prefix="$root/$fuzz_dir/" \
    > "$root/$fuzz_dir/$name.log" 2>&1 || status=$?
  rm -rf "$corpus"
  return $status
}
fuzz_smoke() {  # every target, `jobs` at a time; a summary line each, the failing one's log
  local targets=() target i k name pids batch
  for target in "$fuzz_dir"/fuzz_*; do if [ -x "$target" ]; then targets+=("$target"); fi; done
  for ((i = 0; i < ${#targets[@]}; i += jobs)); do
    pids=()
    batch=("${targets[@]:i:jobs}")
    for target in "${batch[@]}"; do fuzz_one "$target" & pids+=($!); done
    for k in "${!batch[@]}"; do
      name=$(basename "${batch[$k]}")
      if ! wait "${pids[$k]}"; then
        echo "== $name failed:"; tail -n 40 "$fuzz_dir/$name.log"; return 1
      fi
      echo "$name: $(grep -E '^Done [0-9]+ runs' "$fuzz_dir/$name.log" | tail -n 1)"
    done
  done
}
fuzz_pid=""
if [ -d "$fuzz_dir" ]; then
  echo "== fuzz targets (libFuzzer, short smoke run; in the background at the lowest priority, output after the sanitizer suites)"
  fuzz_smoke > "$fuzz_log" 2>&1 &
  fuzz_pid=$!
else
  echo "== clang not found: fuzz targets skipped"
fi
asan_tests_ok=1
run_sanitizer_tests build/asan || asan_tests_ok=0
if [ -n "$fuzz_pid" ]; then
  fuzz_ok=1
  wait "$fuzz_pid" || fuzz_ok=0
  echo "== fuzz targets:"
  cat "$fuzz_log"
  if [ "$fuzz_ok" != 1 ]; then echo "== fuzz smoke failed"; exit 1; fi
fi
if [ "$asan_tests_ok" != 1 ]; then echo "== sanitizer suites failed"; exit 1; fi
echo "== all tests passed in $SECONDS s"
