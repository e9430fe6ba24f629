#!/usr/bin/env bash
# The kernel-camera test (issue 13): the project's camera drivers and visnavd against the kernel's own
# virtual camera drivers, vivid (V4L2) and vimc (media controller, through libcamera), in a qemu VM that boots
# Debian's current kernel. Nothing is installed on the host but the tools below; the kernel packages are
# downloaded with apt-get download and unpacked into a cache directory.
#
#   scripts/test-kernel-cameras.sh [--bin DIR] [--cache DIR] [--out DIR] [--only REGEX] [--no-install]
#
#   --bin DIR     where visnavd, visnav-monitor, test_v4l2 and test_libcamera are (default build/release/bin)
#   --cache DIR   downloads, the unpacked kernel, vimc.ko, the initramfs (default build/kernel-cameras)
#   --out DIR     logs and results.tsv of the run (default build/kernel-cameras/out)
#   --only REGEX  run only the parts/faults whose name matches (e.g. 'disconnect|qbuf'); default: all
#   --no-install  do not install missing packages (fail instead)
#
# Steps on the host: install qemu-system-x86, busybox-static, v4l-utils, libcamera-tools if missing
# (scripts/install-deps.sh --kernel-cameras); download linux-image, linux-headers(-common), linux-kbuild and
# linux-source of the version linux-image-amd64 points to now (not pinned); build vimc out of tree; depmod;
# a busybox initramfs with the 9p and virtio modules; boot qemu-system-x86_64 under TCG (no KVM: nested
# hypervisors do not run Debian's kernel) with the host root shared read-only over 9p and --out shared
# read-write. In the VM the same script runs with --inside (chrooted into the host root): the driver tests on
# vivid and vimc, visnavd on both with telemetry to visnav-monitor, and the fault campaign on vivid's controls.
# Then the summary table. Exit code: 0 every check passed, 1 a check missed, 2 the VM run failed (no
# results), 3 this machine cannot run the test (tools not installable, kernel packages not downloadable).
set -uo pipefail
REPO=$(cd "$(dirname "$0")/.." && pwd)

# ---------------------------------------------------------------------------------------------------------
# Inside the VM (chroot into the host root): the tests themselves.
# ---------------------------------------------------------------------------------------------------------
inside() {
  local bin=$1 out=$2 only=$3
  export HOME=/tmp LIBCAMERA_LOG_LEVELS='*:ERROR' CYCLONEDDS_URI="file://$REPO/config/cyclonedds-loopback.xml"
  mkdir -p "$out/logs"
  : >"$out/results.tsv"
  # shellcheck source=scripts/kernel-cameras/campaign.sh
  source "$REPO/scripts/kernel-cameras/campaign.sh"
  campaign_main "$bin" "$out" "$only"
}

if [ "${1:-}" = "--inside" ]; then
  inside "$2" "$3" "${4:-.}"
  exit 0
fi

# ---------------------------------------------------------------------------------------------------------
# On the host.
# ---------------------------------------------------------------------------------------------------------
BIN=$REPO/build/release/bin
CACHE=$REPO/build/kernel-cameras
OUT=
ONLY=.
INSTALL=1
while [ $# -gt 0 ]; do
  case "$1" in
    --bin) BIN=$(cd "$2" && pwd); shift 2 ;;
    --cache) mkdir -p "$2" && CACHE=$(cd "$2" && pwd); shift 2 ;;
    --out) mkdir -p "$2" && OUT=$(cd "$2" && pwd); shift 2 ;;
    --only) ONLY=$2; shift 2 ;;
    --no-install) INSTALL=0; shift ;;
    -h|--help) sed -n '2,25p' "$0"; exit 0 ;;
    *) echo "test-kernel-cameras: unknown argument $1 (--help)" >&2; exit 2 ;;
  esac
done
OUT=${OUT:-$CACHE/out}
started=$(date +%s)
log() { echo "test-kernel-cameras: $*"; }
die() { echo "test-kernel-cameras: $*" >&2; exit 2; }
cannot() { echo "test-kernel-cameras: cannot run here: $*" >&2; exit 3; }

# The VM mounts its own tmpfs on /tmp, /run and /dev/shm over the shared host root (init below): a checkout,
# binaries, cache or output there would vanish inside it (a clone in /tmp ran nothing and said only "the VM
# produced no results").
for d in "$REPO" "$BIN" "$CACHE" "$OUT"; do
  case "$(realpath -m "$d")/" in
    /tmp/* | /run/* | /dev/shm/*)
      die "$d is under /tmp, /run or /dev/shm, which the VM replaces by its own tmpfs: put the checkout (and --bin, --cache, --out) elsewhere" ;;
  esac
done
for b in visnavd visnav-monitor test_v4l2 test_libcamera; do
  [ -x "$BIN/$b" ] || die "$BIN/$b is missing: build it first (cmake --build build/release --target $b), or pass --bin DIR"
done
if [ "$INSTALL" = 1 ]; then
  "$REPO/scripts/install-deps.sh" --kernel-cameras || cannot "installing the VM tools failed"
fi
for t in qemu-system-x86_64 busybox v4l2-ctl apt-get dpkg-deb make gcc; do
  command -v "$t" >/dev/null || cannot "$t not found (scripts/install-deps.sh --kernel-cameras)"
done

# Debian's current kernel: the versions the meta packages point to today (they move with point releases).
image_pkg=$(apt-cache depends linux-image-amd64 2>/dev/null | sed -n 's/^ *Depends: \(linux-image-[0-9].*-amd64\)$/\1/p' | head -1)
source_pkg=$(apt-cache depends linux-source 2>/dev/null | sed -n 's/^ *Depends: \(linux-source-[0-9.]*\)$/\1/p' | head -1)
[ -n "$image_pkg" ] && [ -n "$source_pkg" ] || cannot "apt-cache knows no linux-image-amd64 / linux-source (apt-get update?)"
ABI=${image_pkg#linux-image-}
series=${source_pkg#linux-source-}
ROOT=$CACHE/root
MODDIR=$ROOT/lib/modules/$ABI
log "kernel $ABI (linux-source-$series), cache $CACHE"

if [ ! -f "$CACHE/.unpacked-$ABI" ]; then
  rm -rf "$CACHE/deb" "$ROOT" "$CACHE/vimc-src"
  mkdir -p "$CACHE/deb" "$ROOT"
  # apt's sandbox user cannot write into a root-owned build tree: download as the caller.
  (cd "$CACHE/deb" && apt-get -o APT::Sandbox::User=root download "$image_pkg" "linux-headers-$ABI" \
     "linux-headers-${ABI%-amd64}-common" "linux-kbuild-$series" "$source_pkg" >/dev/null) \
    || cannot "apt-get download of the kernel packages failed"
  for deb in "$CACHE"/deb/*.deb; do dpkg-deb -x "$deb" "$ROOT" || die "unpacking $deb failed"; done
  touch "$CACHE/.unpacked-$ABI"
fi

if [ ! -f "$MODDIR/extra/vimc.ko" ]; then
  # vimc is not in Debian's kernel config: build it from the source package against the headers package.
  log "building vimc out of tree"
  headers=$ROOT/usr/src/linux-headers-$ABI
  sed -i "s|^include /usr/src/|include $ROOT/usr/src/|" "$headers/Makefile"
  mkdir -p "$CACHE/vimc-src"
  tar -xJf "$ROOT/usr/src/linux-source-$series.tar.xz" -C "$CACHE/vimc-src" --strip-components=4 \
    "linux-source-$series/drivers/media/test-drivers/vimc" || die "vimc sources not found in linux-source"
  make -s -C "$headers" M="$CACHE/vimc-src/vimc" CONFIG_VIDEO_VIMC=m modules -j"$(nproc)" >"$CACHE/vimc-build.log" 2>&1 \
    || die "building vimc failed ($CACHE/vimc-build.log)"
  mkdir -p "$MODDIR/extra"
  cp "$CACHE/vimc-src/vimc/vimc.ko" "$MODDIR/extra/"
  rm -f "$MODDIR/modules.dep"
fi
[ -f "$MODDIR/modules.dep" ] || busybox depmod -b "$ROOT" "$ABI" || die "depmod failed"

# The initramfs: busybox, the modules that reach the 9p share, and an init that chroots into the host root.
INITRD=$CACHE/initramfs-$ABI.cpio.gz
if [ ! -f "$INITRD" ] || [ "$0" -nt "$INITRD" ]; then
  stage=$CACHE/initramfs
  rm -rf "$stage"
  mkdir -p "$stage"/{bin,proc,sys,dev,mnt,tmp} "$stage/lib/modules/$ABI"
  cp "$(command -v busybox)" "$stage/bin/busybox"
  for app in sh mount umount modprobe insmod chroot poweroff sleep cat mkdir echo ip mknod ls; do
    ln -s busybox "$stage/bin/$app"
  done
  needed=" "
  add_module() {  # the module and what modules.dep says it needs
    local path line dep
    line=$(grep -E "(^|/)$1\.ko:" "$MODDIR/modules.dep" | head -1)
    [ -n "$line" ] || die "module $1 not in modules.dep"
    for dep in ${line%%:*} ${line#*:}; do
      case "$needed" in *" $dep "*) ;; *) needed="$needed$dep " ;; esac
    done
  }
  for m in virtio_pci 9pnet_virtio 9p virtio-rng; do add_module "$m"; done
  for path in $needed; do
    mkdir -p "$stage/lib/modules/$ABI/$(dirname "$path")"
    cp "$MODDIR/$path" "$stage/lib/modules/$ABI/$path"
  done
  cp "$MODDIR"/modules.dep "$MODDIR"/modules.alias "$stage/lib/modules/$ABI/" 2>/dev/null
  cat >"$stage/init" <<'INIT'
#!/bin/sh
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
arg() { sed -n "s/.*$1=\([^ ]*\).*/\1/p" /proc/cmdline; }
for m in virtio_pci 9pnet_virtio 9p virtio-rng; do modprobe $m || echo "init: modprobe $m failed"; done
repo=$(arg visnav_repo); bin=$(arg visnav_bin); out=$(arg visnav_out); cache=$(arg visnav_cache)
only=$(arg visnav_only); [ -n "$only" ] || only=.
mount -t 9p -o trans=virtio,version=9p2000.L,ro,cache=loose host /mnt || { echo "init: no host share"; poweroff -f; }
mount -t 9p -o trans=virtio,version=9p2000.L,cache=none out "/mnt$out" || echo "init: no out share"
mount -t proc proc /mnt/proc
mount -t sysfs sys /mnt/sys
mount -t devtmpfs dev /mnt/dev
mount -t tmpfs tmp /mnt/tmp
mount -t tmpfs run /mnt/run
mkdir -p /mnt/dev/shm && mount -t tmpfs shm /mnt/dev/shm
# The camera drivers come from the unpacked kernel in the cache (the host root has no modules of this kernel).
mount --bind "/mnt$cache/root/lib/modules" /lib/modules
for m in vivid vimc; do modprobe $m >"/mnt$out/modprobe-$m.log" 2>&1 || echo "init: modprobe $m failed"; done
ip link set lo up
echo "init: up, running the campaign"
chroot /mnt /bin/bash "$repo/scripts/test-kernel-cameras.sh" --inside "$bin" "$out" "$only"
echo "init: campaign done"
sync
umount "/mnt$out"
poweroff -f
INIT
  chmod +x "$stage/init"
  (cd "$stage" && find . | busybox cpio -o -H newc 2>/dev/null | gzip -1 >"$INITRD") || die "initramfs failed"
fi

mkdir -p "$OUT"
rm -rf "$OUT/logs" "$OUT/results.tsv" "$OUT/console.log"
case "$ONLY" in *' '*) die "--only takes a regex without spaces" ;; esac
log "booting the VM (qemu TCG); console in $OUT/console.log"
vm_start=$(date +%s)
timeout 3600 qemu-system-x86_64 -accel tcg,thread=multi -smp 2 -m 2048 -nographic -no-reboot \
  -kernel "$ROOT/boot/vmlinuz-$ABI" -initrd "$INITRD" \
  -append "console=ttyS0 quiet panic=-1 visnav_repo=$REPO visnav_bin=$BIN visnav_out=$OUT visnav_cache=$CACHE visnav_only=$ONLY" \
  -virtfs "local,path=/,mount_tag=host,security_model=none,readonly=on,multidevs=remap" \
  -virtfs "local,path=$OUT,mount_tag=out,security_model=none,multidevs=remap" \
  -device virtio-rng-pci </dev/null >"$OUT/console.log" 2>&1
vm_rc=$?
vm_s=$(( $(date +%s) - vm_start ))
[ -s "$OUT/results.tsv" ] || { tail -30 "$OUT/console.log"; die "the VM produced no results (qemu exit $vm_rc)"; }

# The summary table.
total=0; failed=0
printf '\n%-34s | %-58s | %-44s | %-9s | %s\n' fault expected seen recovery result
printf '%s\n' "$(printf '%.0s-' $(seq 1 170))"
while IFS=$'\t' read -r name expected seen recovery result; do
  total=$((total + 1))
  [ "$result" = pass ] || failed=$((failed + 1))
  printf '%-34s | %-58s | %-44s | %-9s | %s\n' "$name" "$expected" "$seen" "$recovery" "$result"
done <"$OUT/results.tsv"
elapsed=$(( $(date +%s) - started ))
echo
log "$((total - failed)) of $total checks passed; VM ${vm_s} s, whole run ${elapsed} s; logs in $OUT/logs"
[ "$failed" -eq 0 ] || exit 1
exit 0
