#!/usr/bin/env bash
# ctest package_deb: the jaus-node .deb as cpack makes it from the built tree
#   - control: name, version, computed dependencies (dpkg-shlibdeps) and adduser,
#     conffiles (/etc/jaus/jausd.yaml), maintainer scripts that parse (sh -n);
#   - contents: programs, man pages (gzipped), the unit, configuration, docs;
#   - jausd.service passes systemd-analyze verify, the package lintian (where installed);
#   - dpkg -x into a throwaway root: that jausd, started with that
#     /etc/jaus/jausd.yaml on 127.0.0.50, answers that jausctl's Query
#     Identification, and exits 0 on SIGTERM.
# Usage: check_deb.sh BUILD_DIR VERSION
set -euo pipefail
build=$1 version=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/jaus-package-deb.XXXXXX")
source "$(dirname "$0")/jausd_process.sh"  # cleanup at exit, fail, wait_for, stop_jausd

cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/out" > "$work/cpack.log" 2>&1 ||
  { cat "$work/cpack.log"; fail "cpack"; }
arch=$(dpkg --print-architecture)
deb=$work/out/jaus-node_${version}_${arch}.deb
[ -f "$deb" ] || { ls "$work/out"; fail "no $deb"; }
echo "built $(basename "$deb") ($(du -h "$deb" | cut -f1))"

# Control fields.
info=$(dpkg-deb -f "$deb")
field() { dpkg-deb -f "$deb" "$1"; }
[ "$(field Package)" = jaus-node ] || fail "Package: $(field Package)"
[ "$(field Version)" = "$version" ] || fail "Version: $(field Version), not $version"
depends=$(field Depends)
for dep in adduser libc6 libstdc++6 libyaml-cpp; do
  [[ "$depends" == *"$dep"* ]] || fail "Depends lacks $dep: $depends"
done
[ -n "$(field Maintainer)" ] && [ -n "$(field Description)" ] || fail "no Maintainer or Description: $info"

# Control files: conffiles and maintainer scripts.
dpkg-deb -e "$deb" "$work/control"
[ "$(cat "$work/control/conffiles")" = /etc/jaus/jausd.yaml ] || fail "conffiles: $(cat "$work/control/conffiles")"
for script in postinst prerm postrm; do
  [ -x "$work/control/$script" ] || fail "no executable $script"
  sh -n "$work/control/$script" || fail "$script does not parse"
done
grep -q 'adduser --system' "$work/control/postinst" || fail "postinst creates no system user"
grep -q 'deb-systemd-helper' "$work/control/postinst" || fail "postinst does not enable jausd.service"
grep -q 'rm -rf /var/lib/jaus' "$work/control/postrm" || fail "postrm purge keeps jausd's state"

# Contents.
dpkg-deb -c "$deb" | awk '{print $NF}' > "$work/contents"
for path in ./usr/bin/jausd ./usr/bin/jausctl ./usr/bin/clearpath-sim ./usr/bin/jaus-conform ./usr/bin/jaus-console \
  ./etc/jaus/jausd.yaml ./usr/lib/systemd/system/jausd.service \
  ./usr/share/man/man1/jausd.1.gz ./usr/share/man/man1/jausctl.1.gz ./usr/share/man/man1/clearpath-sim.1.gz \
  ./usr/share/man/man1/jaus-conform.1.gz ./usr/share/man/man1/jaus-console.1.gz ./usr/share/doc/jaus-node/README.md ./usr/share/doc/jaus-node/CHANGELOG.md \
  ./usr/include/jaus/runtime/component.hpp; do
  grep -qx "$path" "$work/contents" || fail "not in the package: $path"
done
grep -q '^\./usr/lib/.*cmake/jaus/jausConfig\.cmake$' "$work/contents" || fail "no CMake package in the .deb"
# The Wireshark plugin, where Debian's Wireshark loads global Lua plugins (docs/wireshark.md).
grep -Eq '^\./usr/lib/([^/]+/)?wireshark/plugins/jaus\.lua$' "$work/contents" || fail "no Wireshark plugin in the .deb"
if grep -q '^\./usr/share/man/man1/.*\.1$' "$work/contents"; then fail "man pages must be gzipped"; fi

# lintian (Debian's package checker), where installed: no error or warning
# but three that need the project's decision, not the packaging's: a license
# (the copyright file), a published maintainer address (JAUS_PACKAGE_MAINTAINER)
# and a Debian changelog.
if command -v lintian > /dev/null; then
  known='no-copyright-file|no-changelog|bogus-mail-host'
  lintian_status=0
  lintian --allow-root --fail-on none "$deb" > "$work/lintian.log" 2>&1 || lintian_status=$?
  if [ "$lintian_status" -ne 0 ] || grep -E '^[EW]: ' "$work/lintian.log" | grep -Ev "^[EW]: jaus-node: ($known)( |$)"; then
    cat "$work/lintian.log"; fail "lintian (exit $lintian_status)"
  fi
  echo "lintian: $(grep -cE '^[EW]: ' "$work/lintian.log") known tags ($known), nothing else"
else
  echo "lintian not found: package not linted"
fi

# The extracted tree.
root=$work/root
dpkg -x "$deb" "$root"
unit=$root/usr/lib/systemd/system/jausd.service
for line in 'User=jaus' 'SupplementaryGroups=dialout' 'ExecStart=/usr/bin/jausd --config /etc/jaus/jausd.yaml' \
  'Restart=on-failure' 'KillSignal=SIGTERM' 'NoNewPrivileges=yes' 'ProtectSystem=strict' 'RuntimeDirectory=jausd'; do
  grep -qx "$line" "$unit" || fail "jausd.service lacks $line"
done
if command -v systemd-analyze > /dev/null; then
  # The unit as installed, but running the extracted jausd (verify checks
  # that ExecStart is executable); no man page lookup. Any line is a finding.
  mkdir "$work/verify"
  sed "s|/usr/bin/jausd|$root/usr/bin/jausd|g" "$unit" > "$work/verify/jausd.service"
  if ! systemd-analyze verify --man=no "$work/verify/jausd.service" > "$work/verify.log" 2>&1 ||
    [ -s "$work/verify.log" ]; then
    cat "$work/verify.log"; fail "systemd-analyze verify jausd.service"
  fi
  echo "systemd-analyze verify: jausd.service ok"
else
  echo "systemd-analyze not found: unit not verified"
fi
"$root/usr/bin/jausd" --version | grep -qx "jausd $version" || fail "extracted jausd --version"
zcat "$root/usr/share/man/man1/jausd.1.gz" | grep -q '^\.TH JAUSD 1' || fail "jausd.1.gz is not a man page"

# The packaged jausd, with the packaged configuration, answers the packaged jausctl.
"$root/usr/bin/jausd" --config "$root/etc/jaus/jausd.yaml" --bind 127.0.0.50:3794 > "$work/jausd.log" 2>&1 &
jausd_pid=$!
wait_for 60 grep -q 'listening on 127.0.0.50:3794' "$work/jausd.log" || { cat "$work/jausd.log"; fail "jausd did not start"; }
query() {
  "$root/usr/bin/jausctl" query 1.1.1.1 "Query Identification" --fields '{"query_type":2}' \
    --to 127.0.0.50 --bind 127.0.0.51:0 --timeout 2 > "$work/reply.json" 2> "$work/jausctl.err"
}
wait_for 60 query || { cat "$work/jausctl.err" "$work/jausd.log"; fail "no answer to Query Identification"; }
grep -q '"name":"Report Identification"' "$work/reply.json" || { cat "$work/reply.json"; fail "not a Report Identification"; }
echo "jausctl: $(cut -c1-160 "$work/reply.json")"

stop_jausd
grep -q 'stop\|shut' "$work/jausd.log" || { cat "$work/jausd.log"; fail "jausd logged no orderly stop"; }
echo "PASS"
