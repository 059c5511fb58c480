#!/usr/bin/env bash
# ctest package_install_and_build_component: `cmake --install` of the built
# tree into a temporary prefix puts the programs, libraries, headers, CMake
# package, configuration, man pages and docs where GNUInstallDirs says; then
# example_component (a component of its own on jaus::runtime, and a program
# on jaus::conform, the top of the library graph) is configured with
# find_package(jaus) against that prefix only, built and run; its wheel
# odometer, built as a component plugin (jaus_add_component_plugin), is
# loaded into the installed jausd from a YAML on 127.0.0.80 and answers the
# installed jausctl; jausd stops on SIGTERM with exit 0.
# Usage: install_and_build_component.sh BUILD_DIR EXAMPLE_SOURCE_DIR VERSION
set -euo pipefail
build=$1 example=$2 version=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/jaus-package-install.XXXXXX")
source "$(dirname "$0")/jausd_process.sh"  # cleanup at exit, fail, wait_for, stop_jausd
prefix=$work/prefix

cmake --install "$build" --prefix "$prefix" > "$work/install.log" || { cat "$work/install.log"; fail "cmake --install"; }

libdir=$(cd "$prefix" && ls -d lib/*-linux-gnu 2>/dev/null || echo lib)
for path in bin/jausd bin/jausctl bin/clearpath-sim bin/jaus-conform \
  etc/jaus/jausd.yaml \
  "$libdir"/libjaus_runtime.a "$libdir"/libjaus_core.a "$libdir"/libjaus_base.a \
  "$libdir"/cmake/jaus/jausConfig.cmake "$libdir"/cmake/jaus/jausConfigVersion.cmake "$libdir"/cmake/jaus/jausTargets.cmake \
  include/jaus/runtime/component.hpp include/jaus/base/version.hpp include/jaus/components/visual_sensor.hpp \
  include/jaus/runtime/component_plugin.hpp include/jaus/testing/memory_link.hpp "$libdir"/cmake/jaus/jausPlugin.cmake \
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

# The plugin: it links no jaus library (jausd carries the one copy).
plugin=$work/example/libwheel_odometer.so
[ -f "$plugin" ] || fail "jaus_add_component_plugin built no $plugin"
if readelf -d "$plugin" | grep -q 'NEEDED.*jaus'; then fail "$plugin links a jaus library"; fi
nm -D --defined-only "$plugin" | grep -q ' T jaus_component_plugin$' || fail "$plugin does not export jaus_component_plugin"
# Loaded by the installed jausd from a YAML naming it (relative to the YAML) and its kind.
cat > "$work/example/odometer.yaml" <<YAML
plugins:
  - libwheel_odometer.so
components:
  - kind: node_manager
  - kind: wheel_odometer
    name: wheel odometer
    options:
      speed_mps: 1.5
      yaw_rate_rps: 0.25
YAML
"$prefix/bin/jausd" --config "$work/example/odometer.yaml" --check-config ||
  fail "installed jausd rejects the plugin's configuration"
printf 'plugins: [libwheel_odometer.so]\ncomponents:\n  - kind: node_manager\n  - kind: wheel_odometer\n    options:\n      speed_mps: 99\n' \
  > "$work/example/bad_option.yaml"
status=0
"$prefix/bin/jausd" --config "$work/example/bad_option.yaml" --check-config 2> "$work/bad_option.err" || status=$?
[ "$status" -eq 2 ] && grep -q "bad_option.yaml:6: wheel_odometer option 'speed_mps' must be" "$work/bad_option.err" ||
  { cat "$work/bad_option.err"; fail "the plugin's option check: exit $status"; }

"$prefix/bin/jausd" --config "$work/example/odometer.yaml" --bind 127.0.0.80:3794 > "$work/jausd.log" 2>&1 &
jausd_pid=$!
wait_for 60 grep -q 'listening on 127.0.0.80:3794' "$work/jausd.log" || { cat "$work/jausd.log"; fail "jausd did not start"; }
grep -q "plugin 'example_wheel_odometer' (.*libwheel_odometer.so): component kinds wheel_odometer" "$work/jausd.log" ||
  { cat "$work/jausd.log"; fail "jausd did not log the plugin and its kinds"; }
query() {
  "$prefix/bin/jausctl" query 1.1.42.1 "Query Velocity State" --pv 41 \
    --to 127.0.0.80 --bind 127.0.0.80:0 --timeout 2 > "$work/reply.json" 2> "$work/jausctl.err"
}
wait_for 60 query || { cat "$work/jausctl.err" "$work/jausd.log"; fail "no answer to Query Velocity State"; }
grep -q '"name":"Report Velocity State"' "$work/reply.json" || { cat "$work/reply.json"; fail "not a Report Velocity State"; }
# Scaled integers on the wire: 1.5 and 0.25 to within their resolution.
grep -Eq '"velocity_x_mps":1\.(5|49999)' "$work/reply.json" && grep -Eq '"yaw_rate_rps":0\.(25|24999)' "$work/reply.json" ||
  { cat "$work/reply.json"; fail "not what the odometer measured (speed_mps 1.5, yaw_rate_rps 0.25)"; }
echo "jausctl: $(cut -c1-200 "$work/reply.json")"

stop_jausd
echo "PASS"
