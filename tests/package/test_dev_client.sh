#!/usr/bin/env bash
# ctest package_dev_client (fixture visnav_debs: the packages package_deb_contents built): a ground client
# built from the installed files alone, against the system's Cyclone DDS, receives visnavd's telemetry.
#  1. unpacks visnav, visnav-dev (and libvisnav<N> when built) into a fresh staging root with dpkg-deb -x;
#  2. builds tests/package/dev_client/visnav_pose_client.c twice, from that root only: with pkg-config
#     (visnav-idl.pc, prefix redefined to the root) and with CMake (find_package(visnav-idl),
#     CMAKE_PREFIX_PATH = the root); neither sees the source tree's idl/ or the build folder;
#  3. runs the *packaged* visnavd (from the root, its packaged /etc/visnav/visnavd.toml with the domain and
#     partition changed, on the packaged loopback Cyclone config) on an own DDS domain and partition, waiting
#     for both clients (--wait-subscribers 2), and each client must receive COUNT PoseEstimate samples with
#     rising sample numbers.
# usage: test_dev_client.sh PACKAGE_DIR SOURCE_DIR
set -euo pipefail
work=$1
source_dir=$2
count=20
shopt -s nullglob
debs=("$work"/visnav_*.deb "$work"/visnav-dev_*.deb "$work"/libvisnav[0-9]*_*.deb)
if [ ${#debs[@]} -lt 2 ]; then
  echo "test_dev_client: packages missing in $work (run package_deb_contents first)" >&2
  exit 1
fi
root=$work/client_root
rm -rf "$root" "$work/client_pc" "$work/client_cmake"
mkdir -p "$root" "$work/client_pc"
for deb in "${debs[@]}"; do
  dpkg-deb -x "$deb" "$root"
  echo "test_dev_client: unpacked $(basename "$deb")"
done
client_src=$source_dir/tests/package/dev_client

# pkg-config: only the root's .pc directory is added; CycloneDDS.pc comes from the system. The redefined prefix
# applies to every package pkg-config reads, so Cyclone's flags point into the root as well; its headers and
# libddsc.so are then found in the compiler's and linker's default /usr paths, i.e. the system's.
pcdir=$(dirname "$(find "$root/usr/lib" -name visnav-idl.pc -print -quit)")
flags=$(PKG_CONFIG_PATH=$pcdir pkg-config --define-variable=prefix="$root/usr" --cflags --libs visnav-idl)
echo "test_dev_client: pkg-config visnav-idl: $flags"
cc -std=c11 -Wall -Wextra -Werror -o "$work/client_pc/visnav_pose_client" "$client_src/visnav_pose_client.c" \
  $flags -lm
# CMake: the package's config files locate themselves (no absolute build path in them).
cmake -S "$client_src" -B "$work/client_cmake" -G Ninja -DCMAKE_PREFIX_PATH="$root/usr" \
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF >"$work/client_cmake.log" 2>&1 || { cat "$work/client_cmake.log"; exit 1; }
cmake --build "$work/client_cmake" >>"$work/client_cmake.log" 2>&1 || { cat "$work/client_cmake.log"; exit 1; }
echo "test_dev_client: both clients built from $root"

# An own domain (100..199) and partition per run: parallel tests and a running visnavd never mix.
domain=$((100 + $$ % 100))
partition=devclient-$$
config=$work/visnavd-client.toml
sed -e "s|\"/usr/share/visnav/|\"$root/usr/share/visnav/|" -e "s|^domain_id = .*|domain_id = $domain|" \
  -e "s|^partition = .*|partition = \"$partition\"|" "$root/etc/visnav/visnavd.toml" >"$config"
grep -q "^partition = \"$partition\"" "$config" && grep -q "^domain_id = $domain" "$config"
export CYCLONEDDS_URI=file://$root/etc/visnav/cyclonedds.xml
"$work/client_pc/visnav_pose_client" "$domain" "$partition" $count 60 >"$work/client_pc.out" 2>&1 &
pc_pid=$!
"$work/client_cmake/visnav_pose_client" "$domain" "$partition" $count 60 >"$work/client_cmake.out" 2>&1 &
cmake_pid=$!
daemon_status=0
"$root/usr/bin/visnavd" --config "$config" --cycles $((count + 10)) --wait-subscribers 2 --wait-timeout 30 \
  >"$work/visnavd-client.log" 2>&1 || daemon_status=$?
pc_status=0
cmake_status=0
wait $pc_pid || pc_status=$?
wait $cmake_pid || cmake_status=$?
tail -n 2 "$work/client_pc.out" "$work/client_cmake.out"
if [ $daemon_status -ne 0 ] || [ $pc_status -ne 0 ] || [ $cmake_status -ne 0 ]; then
  echo "test_dev_client: visnavd exit $daemon_status, pkg-config client $pc_status, CMake client $cmake_status" >&2
  tail -n 20 "$work/visnavd-client.log" >&2
  exit 1
fi
echo "test_dev_client: both clients received $count PoseEstimate samples from the packaged visnavd (domain $domain)"
