#!/usr/bin/env bash
# ctest package_install_and_build_component: `cmake --install` of the built
# tree into a temporary prefix puts the programs, libraries, headers, CMake
# package, configuration, man pages and docs where GNUInstallDirs says; then
# example_component (a component of its own on jaus::runtime, and a program
# on jaus::conform, the top of the library graph) is configured with
# find_package(jaus) against that prefix only, built and run.
# Usage: install_and_build_component.sh BUILD_DIR EXAMPLE_SOURCE_DIR VERSION
set -euo pipefail
build=$1 example=$2 version=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/jaus-package-install.XXXXXX")
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix

fail() { echo "FAIL: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$prefix" > "$work/install.log" || { cat "$work/install.log"; fail "cmake --install"; }

libdir=$(cd "$prefix" && ls -d lib/*-linux-gnu 2>/dev/null || echo lib)
for path in bin/jausd bin/jausctl bin/clearpath-sim bin/jaus-conform \
  etc/jaus/jausd.yaml \
  "$libdir"/libjaus_runtime.a "$libdir"/libjaus_core.a "$libdir"/libjaus_base.a \
  "$libdir"/cmake/jaus/jausConfig.cmake "$libdir"/cmake/jaus/jausConfigVersion.cmake "$libdir"/cmake/jaus/jausTargets.cmake \
  include/jaus/runtime/component.hpp include/jaus/base/version.hpp include/jaus/components/visual_sensor.hpp \
  share/man/man1/jausd.1.gz share/man/man1/jausctl.1.gz share/man/man1/clearpath-sim.1.gz share/man/man1/jaus-conform.1.gz \
  share/doc/jaus-node/README.md share/doc/jaus-node/CHANGELOG.md share/doc/jaus-node/docs/configuration.md \
  lib/systemd/system/jausd.service; do
  [ -e "$prefix/$path" ] || fail "not installed: $path"
done
[ -x "$prefix/bin/jausd" ] || fail "bin/jausd is not executable"
# Internal targets stay inside the build: the exported interface names none.
source_dir=$(cd "$example/../../.." && pwd)
if grep -n -e jaus_warnings -e jausd_config -e jausctl_commands -e "$build" -e "$source_dir" \
  "$prefix/$libdir"/cmake/jaus/*.cmake; then
  fail "the exported CMake package names an internal target or the build tree"
fi
grep -q "kVersion = \"$version\"" "$prefix/include/jaus/base/version.hpp" || fail "installed version.hpp is not $version"
"$prefix/bin/jausd" --config "$prefix/etc/jaus/jausd.yaml" --check-config > /dev/null || fail "installed jausd rejects installed jausd.yaml"
echo "installed into $prefix ($(find "$prefix" -type f | wc -l) files)"

# The example, as another project: only the installed prefix is searched.
cmake -S "$example" -B "$work/example" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" \
  > "$work/configure.log" 2>&1 || { cat "$work/configure.log"; fail "configuring example_component against $prefix"; }
cmake --build "$work/example" > "$work/build.log" 2>&1 || { cat "$work/build.log"; fail "building example_component"; }
"$work/example/example_component" || fail "example_component"
"$work/example/count_conformance_cases" || fail "count_conformance_cases (jaus::conform from the installed tree)"
echo "PASS"
