#!/usr/bin/env bash
# The visnav .deb in a clean Debian 12 root: install, enable, start, upgrade, remove, purge, with real dpkg
# running the package's real maintainer scripts (cmake/deb/{postinst,prerm,postrm}) in a chroot.
#   scripts/test-package.sh [DEB]      # DEB default: build/release/package_test/visnav_<version>_amd64.deb
#                                      # (ctest -R package_deb_contents in build/release makes it)
# Root: `debootstrap --variant=minbase bookworm` plus systemd (for systemctl's offline unit-file operations,
# systemd-sysusers, deb-systemd-helper) and the package's run-time Depends, taken from the machine's own
# Debian mirror (its apt sources) once and cached in /var/cache/visnav/package-root/base.tar (outside the
# clone, so CI on the same machine reuses it: first run about 4 min, then about 20 s; VISNAV_PACKAGE_CACHE
# moves it); every run unpacks a fresh copy into build/package-root/root. No systemd runs in a chroot, so /usr/bin/systemctl is diverted to a stand-in (below) that records
# every call: unit-file verbs (enable, disable, is-enabled, mask, ...) go to the real systemctl, which edits
# the links offline; runtime verbs (start, stop, try-restart, is-active, daemon-reload) are recorded and
# answered from a state file. /run/systemd/system exists, so the maintainer scripts act as on a booted system.
# Depends built beside the .deb (libvisnav<N>) are installed from their .deb with it and purged after it.
# Checks: the visnav user (sysusers) in group video; conffiles; visnav-dev beside it ships the ROS 2 .msg
# files (its file list: it is not installed); enable makes the multi-user.target.wants
# link; an upgrade (the same package repacked as <version>+1) try-restarts the running service and does not
# stop it; remove stops it; purge removes the enable link, /etc/visnav and the helper's state, and leaves no
# file of the package: the root's file list after purge equals the one before install, except for dpkg's and
# apt's own records, logs, and the visnav user and group, which stay (Debian policy: a uid may own files
# elsewhere; the postrm says so).
# Needs root (chroot), debootstrap (scripts/install-deps.sh) and the Debian mirror on the first run.
# Exit 0 all checks passed, 1 a check failed, 3 cannot run here (no root, no debootstrap, no mirror).
#   scripts/test-package.sh --self-test [DEB]   # the checks can fail: the same package with prerm and postrm
#                                      # emptied must fail the stop-on-remove and clean-purge checks (exit 0 if so)
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = --self-test ]; then
  shift
  version=$(sed -n 's/^project(visnav VERSION \([0-9.]*\).*/\1/p' CMakeLists.txt)
  deb=$(realpath -m "${1:-build/release/package_test/visnav_${version}_amd64.deb}")
  mutant=build/package-root/mutant
  rm -rf "$mutant" && mkdir -p "$mutant"
  dpkg-deb -R "$deb" "$mutant/pkg"
  for script in prerm postrm; do printf '#!/bin/sh\nexit 0\n' >"$mutant/pkg/DEBIAN/$script"; done
  # Beside it the same sibling packages (libvisnav<N>, visnav-dev), so only the maintainer scripts differ.
  for sibling in "$(dirname "$deb")"/libvisnav[0-9]*_*.deb "$(dirname "$deb")"/visnav-dev_*.deb; do
    [ -f "$sibling" ] && cp "$sibling" "$mutant/"
  done
  dpkg-deb --root-owner-group -b "$mutant/pkg" "$mutant/$(basename "$deb")" >/dev/null
  status=0
  "$0" "$mutant/$(basename "$deb")" >"$mutant/run.log" 2>&1 || status=$?
  grep -E 'FAIL' "$mutant/run.log" || true
  if [ "$status" -eq 1 ] && grep -q 'FAIL remove: visnavd stopped' "$mutant/run.log" &&
    grep -q 'FAIL purge: no multi-user.target.wants link' "$mutant/run.log"; then
    echo "test-package: self-test passed: emptied prerm/postrm are caught"
    exit 0
  fi
  echo "test-package: self-test FAILED: emptied prerm/postrm went unnoticed (exit $status)"
  exit 1
fi
t0=$(date +%s)
version=$(sed -n 's/^project(visnav VERSION \([0-9.]*\).*/\1/p' CMakeLists.txt)
deb=$(realpath -m "${1:-build/release/package_test/visnav_${version}_amd64.deb}")
cache=build/package-root
base_cache=${VISNAV_PACKAGE_CACHE:-/var/cache/visnav/package-root}
root=$PWD/$cache/root
if [ "$(id -u)" -ne 0 ] || ! command -v debootstrap >/dev/null; then
  echo "test-package: needs root and debootstrap (scripts/install-deps.sh)" >&2
  exit 3
fi
if [ ! -f "$deb" ]; then
  echo "test-package: $deb missing (ctest -R package_deb_contents builds it)" >&2
  exit 1
fi
failures=0
ok() {  # ok DESCRIPTION COMMAND...: one line per check, counted
  local desc=$1
  shift
  if "$@"; then echo "test-package: ok   $desc"; else
    echo "test-package: FAIL $desc"
    failures=$((failures + 1))
  fi
}
cleanup() {
  local m
  for m in proc dev; do
    if mountpoint -q "$root/$m" 2>/dev/null; then umount -l "$root/$m"; fi
  done
  return 0
}
trap cleanup EXIT

# 1. The base root, cached: minbase + systemd + the package's Depends (from dpkg-deb, versions dropped) that
# Debian has; a Depends built beside it (libvisnav<N>, the C ABI library) is installed from its .deb instead.
siblings=()
depends=""
for dep in $(dpkg-deb -f "$deb" Depends | tr ',' '\n' | sed -e 's/[(|].*//' -e 's/ //g' | grep -v '^$' | sort -u); do
  sibling=$(ls "$(dirname "$deb")/${dep}_"*.deb 2>/dev/null | head -n 1 || true)
  if [ -n "$sibling" ]; then siblings+=("$sibling"); else depends+="${depends:+,}$dep"; fi
done
include="systemd,$depends"
mkdir -p "$cache" "$base_cache"
if [ ! -f "$base_cache/base.tar" ] || [ "$(cat "$base_cache/base.include" 2>/dev/null)" != "$include" ]; then
  mirror=$(sed -n 's/^URIs: *\([^ ]*\).*/\1/p' /etc/apt/sources.list.d/debian.sources 2>/dev/null | head -n 1)
  [ -n "$mirror" ] || mirror=$(awk '$1 == "deb" && $3 == "bookworm" {print $2; exit}' /etc/apt/sources.list 2>/dev/null)
  if [ -z "$mirror" ]; then
    echo "test-package: no Debian mirror in this machine's apt sources" >&2
    exit 3
  fi
  rm -rf "$cache/base"
  echo "test-package: debootstrap bookworm (minbase + $include) from the machine's mirror"
  if ! debootstrap --variant=minbase --include="$include" bookworm "$cache/base" "$mirror" \
      >"$cache/debootstrap.log" 2>&1; then
    tail -n 20 "$cache/debootstrap.log" >&2
    echo "test-package: debootstrap failed (log: $cache/debootstrap.log)" >&2
    exit 3
  fi
  rm -rf "$cache/base/var/cache/apt/archives/"*.deb
  tar -C "$cache/base" -cf "$base_cache/base.tar" .
  echo "$include" >"$base_cache/base.include"
  rm -rf "$cache/base"
  echo "test-package: base root cached in $base_cache ($(du -m "$base_cache/base.tar" | cut -f1) MB) at $(( $(date +%s) - t0 )) s"
fi
cleanup  # a run killed before its trap leaves /proc and /dev mounted: never delete through them
rm -rf --one-file-system "$root"
mkdir -p "$root"
tar -C "$root" -xf "$base_cache/base.tar"
mount -t proc proc "$root/proc"
mount --bind /dev "$root/dev"
in_root() { chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin "$@"; }

# 2. The systemctl stand-in.
in_root dpkg-divert --quiet --local --rename --add /usr/bin/systemctl
cat >"$root/usr/bin/systemctl" <<'EOF'
#!/bin/sh
# test-package.sh's stand-in: records every call in /var/log/systemctl.calls; runtime verbs answered from
# /run/fake-systemd/<unit>.active, unit-file verbs done by the real systemctl (offline in a chroot).
echo "$*" >>/var/log/systemctl.calls
verb=""
unit=""
for arg in "$@"; do
  case "$arg" in
    -*) ;;
    *) if [ -z "$verb" ]; then verb=$arg; elif [ -z "$unit" ]; then unit=$arg; fi ;;
  esac
done
state=/run/fake-systemd/$unit.active
mkdir -p /run/fake-systemd
case "$verb" in
  daemon-reload | daemon-reexec | reset-failed) exit 0 ;;
  start | restart | reload-or-restart) touch "$state"; echo "$verb $unit" >>/var/log/systemctl.actions ;;
  stop) rm -f "$state"; echo "stop $unit" >>/var/log/systemctl.actions ;;
  try-restart | condrestart | try-reload-or-restart)
    [ -e "$state" ] && echo "restart $unit (running)" >>/var/log/systemctl.actions ;;
  is-active) [ -e "$state" ] ;;
  is-system-running) echo running ;;
  *) SYSTEMD_OFFLINE=1 exec /usr/bin/systemctl.distrib "$@" ;;  # /run/systemd/system exists: say "offline"
esac
EOF
chmod 755 "$root/usr/bin/systemctl"
mkdir -p "$root/run/systemd/system"
: >"$root/var/log/systemctl.calls"
: >"$root/var/log/systemctl.actions"
snapshot() {  # every path in the root but dpkg's/apt's records, logs, caches and the stand-in's state
  (cd "$root" && find . -xdev \( -path ./proc -o -path ./dev -o -path ./run -o -path ./var/lib/dpkg \
    -o -path ./var/log -o -path ./var/cache -o -path ./tmp -o -path ./var/lib/apt \) -prune -o -print | sort)
}
snapshot >"$cache/before.txt"

# 3. Install (with the sibling packages it depends on).
cp "$deb" "$root/tmp/visnav.deb"
sibling_names=()
for sibling in "${siblings[@]}"; do
  cp "$sibling" "$root/tmp/"
  sibling_names+=("$(dpkg-deb -f "$sibling" Package)")
done
echo "test-package: dpkg -i $(basename "$deb") ${siblings[*]/#*\//}"
in_root sh -c 'dpkg -i /tmp/*.deb' >"$cache/install.log" 2>&1 || { cat "$cache/install.log"; exit 1; }
ok "installed: dpkg status 'install ok installed'" \
  test "$(in_root dpkg-query -W -f='${Status}' visnav)" = "install ok installed"
ok "sysusers: user visnav exists, in group video" sh -c "chroot '$root' id -nG visnav | grep -qw video"
ok "visnavd --check accepts the packaged /etc/visnav/visnavd.toml" \
  in_root /usr/bin/visnavd --check /etc/visnav/visnavd.toml
for name in "${sibling_names[@]}"; do
  case "$name" in libvisnav[0-9]*)
    ok "$name: its ldconfig trigger put libvisnav.so.${name#libvisnav} in the linker cache" \
      sh -c "chroot '$root' /sbin/ldconfig -p | grep -q 'libvisnav.so.${name#libvisnav} '" ;;
  esac
done
ok "not enabled on install (no enable link)" test ! -e "$root/etc/systemd/system/multi-user.target.wants/visnavd.service"
ok "conffiles registered" sh -c "chroot '$root' dpkg-query -W -f='\${Conffiles}' visnav | grep -q /etc/visnav/visnavd.toml"
# visnav-dev, built beside it, is not installed here (it depends on the build machine's -dev packages); its
# file list must hold the ROS 2 message package: every .msg of idl/ros2/visnav_msgs/msg, and package.xml.
dev_deb=$(ls "$(dirname "$deb")"/visnav-dev_*.deb 2>/dev/null | head -n 1 || true)
ros2_msgs_shipped() {
  [ -n "$dev_deb" ] || return 1
  local listing file
  listing=$(dpkg-deb -c "$dev_deb") || return 1
  for file in idl/ros2/visnav_msgs/msg/*.msg idl/ros2/visnav_msgs/package.xml; do
    grep -q " \./usr/share/visnav/ros2/${file#idl/ros2/}\$" <<<"$listing" || { echo "  missing: $file" >&2; return 1; }
  done
}
ok "visnav-dev ships the ROS 2 .msg files in /usr/share/visnav/ros2/visnav_msgs ($(ls idl/ros2/visnav_msgs/msg/*.msg | wc -l) of them)" \
  ros2_msgs_shipped

# 4. Enable and start as an operator would.
in_root systemctl enable visnavd.service >>"$cache/install.log" 2>&1
in_root systemctl start visnavd.service
link=$(readlink "$root/etc/systemd/system/multi-user.target.wants/visnavd.service" || true)
ok "enable: multi-user.target.wants/visnavd.service -> the packaged unit ($link)" \
  sh -c "case '$link' in /lib/systemd/system/visnavd.service | /usr/lib/systemd/system/visnavd.service) ;; *) false ;; esac"
# An operator's edit of a conffile survives the upgrade.
echo "# operator edit" >>"$root/etc/visnav/visnavd.toml"

# 5. Upgrade: the same package repacked with version <version>+1.
rm -rf "$cache/repack" && mkdir -p "$cache/repack"
dpkg-deb -R "$deb" "$cache/repack/pkg"
sed -i "s/^Version: .*/Version: ${version}+1/" "$cache/repack/pkg/DEBIAN/control"
dpkg-deb --root-owner-group -b "$cache/repack/pkg" "$root/tmp/visnav-upgrade.deb" >/dev/null
: >"$root/var/log/systemctl.actions"
in_root dpkg -i /tmp/visnav-upgrade.deb >"$cache/upgrade.log" 2>&1 || { cat "$cache/upgrade.log"; exit 1; }
ok "upgrade: version ${version}+1 installed" test "$(in_root dpkg-query -W -f='${Version}' visnav)" = "${version}+1"
ok "upgrade: the running visnavd is restarted, once, and not stopped" \
  test "$(cat "$root/var/log/systemctl.actions")" = "restart visnavd.service (running)"
ok "upgrade: the enable link stays" test -L "$root/etc/systemd/system/multi-user.target.wants/visnavd.service"
ok "upgrade: the operator's conffile edit survives" grep -q "^# operator edit" "$root/etc/visnav/visnavd.toml"

# 6. Remove: stops the service, keeps the conffiles.
: >"$root/var/log/systemctl.actions"
in_root dpkg --remove visnav >"$cache/remove.log" 2>&1 || { cat "$cache/remove.log"; exit 1; }
ok "remove: visnavd stopped" test "$(cat "$root/var/log/systemctl.actions")" = "stop visnavd.service"
ok "remove: binaries gone, conffiles kept (dpkg state config-files)" sh -c \
  "[ ! -e '$root/usr/bin/visnavd' ] && [ -f '$root/etc/visnav/visnavd.toml' ] &&
   [ \"\$(chroot '$root' dpkg-query -W -f='\${Status}' visnav)\" = 'deinstall ok config-files' ]"

# 7. Purge: nothing left but the user.
in_root dpkg --purge visnav >"$cache/purge.log" 2>&1 || { cat "$cache/purge.log"; exit 1; }
ok "purge: no multi-user.target.wants link (dangling or not)" \
  sh -c "! ls -A '$root'/etc/systemd/system/*.wants/visnavd.service >/dev/null 2>&1"
ok "purge: /etc/visnav gone" test ! -e "$root/etc/visnav"
ok "purge: no mask link left" test ! -e "$root/etc/systemd/system/visnavd.service"
ok "purge: package unknown to dpkg" sh -c "! chroot '$root' dpkg-query -W visnav >/dev/null 2>&1"
ok "purge: the visnav user stays (policy)" sh -c "chroot '$root' getent passwd visnav >/dev/null"
if [ ${#sibling_names[@]} -gt 0 ]; then
  in_root dpkg --purge "${sibling_names[@]}" >>"$cache/purge.log" 2>&1 || { cat "$cache/purge.log"; exit 1; }
fi
snapshot >"$cache/after.txt"
# Allowed differences: the user's lines live in these files, which exist before and after (same paths), and
# deb-systemd-helper's state folders (empty after purge; checked below).
leftover=$(comm -13 "$cache/before.txt" "$cache/after.txt" |
  grep -v -e '^\./var/lib/systemd/deb-systemd-helper-\(enabled\|masked\)$' -e '^\./etc/\(passwd\|group\|shadow\|gshadow\)-$' || true)
missing=$(comm -23 "$cache/before.txt" "$cache/after.txt" || true)
ok "purge: no file of the package left (file list = before install)" test -z "$leftover$missing"
[ -n "$leftover$missing" ] && printf 'left: %s\nmissing: %s\n' "$leftover" "$missing"
ok "purge: deb-systemd-helper state holds nothing for visnavd" \
  sh -c "! find '$root/var/lib/systemd' -name '*visnavd*' | grep -q ."
echo "test-package: systemctl calls made by the maintainer scripts and the operator:"
sed 's/^/  /' "$root/var/log/systemctl.calls"
echo "test-package: $(( $(date +%s) - t0 )) s"
if [ "$failures" -ne 0 ]; then
  echo "test-package: $failures check(s) failed"
  exit 1
fi
echo "test-package: all checks passed"
