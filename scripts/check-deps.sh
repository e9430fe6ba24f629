#!/usr/bin/env bash
# Dependency direction of the flight libraries and drivers (README.md, "The house"): every
# `#include "visnav/<folder>/..."` in fsw/<X> or drivers/<X> must name X itself or a folder X may use, and only
# fsw/telemetry speaks DDS (<dds/...>, "idl/..."), also not through a header: fsw/telemetry's public headers
# (fsw/telemetry/include) include no DDS header, its DDS-level headers (fsw/telemetry/include-dds: for ground
# tools and tests) are included by no other fsw/ or drivers/ folder, and no other folder's CMakeLists.txt links
# Cyclone or the DDS-level target (fsw/telemetry/README.md, "Interfaces"). The graph below is one-way (checked: no cycle); a folder may
# use what its direct dependencies may use. A CMakeLists.txt that adds another folder's include directory by
# path (the way round the graph) is held to the same rule. Prints file:line and the offending include for each
# violation and exits 1; exits 0 when there is none. CI runs it as the ctest `dependency_direction` (label
# lint), and its self-test as `dependency_direction_self_test`.
#   scripts/check-deps.sh [--root DIR]   check the tree at DIR (default: this repository)
#   scripts/check-deps.sh --self-test    plant violations in a temporary tree and check they are caught
set -uo pipefail

# Direct dependencies of each folder (fsw/<name> or drivers/<name>; its headers are visnav/<name>/...).
declare -A DIRECT=(
  [core]=""
  [geometry]="core"
  [solver]="core"
  [nearrange]="geometry solver"
  [farrange]="geometry"
  [acquisition]="nearrange"
  [navigation]="acquisition farrange nearrange"
  [executive]="core"
  [io]="geometry"
  [telemetry]="navigation io"
  [app]="navigation executive telemetry io camera v4l2 libcamera replay synthetic"
  [capi]="app navigation executive io"
  [camera]="core"
  [v4l2]="camera"
  [libcamera]="camera"
  [replay]="camera io"
  [synthetic]="camera geometry io"
)
# The only folder that may include the DDS C API or the idlc-generated types.
DDS_FOLDER=telemetry
DDS_INCLUDE=include-dds  # its DDS-level headers (ground tools, tests); include/ is its DDS-free interface

declare -A ALLOWED=()  # folder -> " a b c " (transitive closure, with spaces around every name)

# Fills ALLOWED[$1]; $2 is the path of folders being expanded (a folder met again on it is a cycle).
closure() {
  local folder=$1 path=$2 dep result=" "
  [[ -n ${ALLOWED[$folder]+x} ]] && return 0
  for dep in ${DIRECT[$folder]}; do
    if [[ -z ${DIRECT[$dep]+x} ]]; then
      echo "check-deps: the graph names an unknown folder '$dep' (used by $folder)" >&2
      return 1
    fi
    if [[ " $path " == *" $dep "* ]]; then
      echo "check-deps: the graph has a cycle: $path $dep" >&2
      return 1
    fi
    closure "$dep" "$path $dep" || return 1
    result+="$dep ${ALLOWED[$dep]# }"
  done
  ALLOWED[$folder]=" $(tr ' ' '\n' <<<"$result" | sed '/^$/d' | sort -u | tr '\n' ' ')"
}

check_tree() {
  local root=$1 violations=0 folder dir
  for folder in "${!DIRECT[@]}"; do closure "$folder" "$folder" || return 2; done
  local -a folders=()
  for dir in "$root"/fsw/*/ "$root"/drivers/*/; do
    [[ -d $dir ]] && folders+=("${dir%/}")
  done
  for dir in "${folders[@]}"; do
    folder=$(basename "$dir")
    if [[ -z ${DIRECT[$folder]+x} ]]; then
      echo "${dir#"$root"/}: folder not in the dependency graph (add it to scripts/check-deps.sh and README.md)"
      violations=$((violations + 1))
      continue
    fi
    local allowed=${ALLOWED[$folder]}
    local file line text target
    # Includes of another folder's headers.
    while IFS=: read -r file line text; do
      target=$(sed -E 's/.*#[[:space:]]*include[[:space:]]*[<"]visnav\/([A-Za-z0-9_]+)\/.*/\1/' <<<"$text")
      [[ $target == "$folder" || $allowed == *" $target "* ]] && continue
      if [[ -z ${DIRECT[$target]+x} ]]; then
        echo "${file#"$root"/}:$line: $text  <- no folder '$target' in the dependency graph"
      else
        echo "${file#"$root"/}:$line: $text  <- $folder may use only:${allowed% }"
      fi
      violations=$((violations + 1))
    done < <(grep -rnE --include='*.cpp' --include='*.hpp' --include='*.h' --include='*.c' \
               '^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]visnav/[A-Za-z0-9_]+/' "$dir" 2>/dev/null)
    # DDS outside telemetry: directly, or through one of telemetry's DDS-level headers.
    if [[ $folder != "$DDS_FOLDER" ]]; then
      while IFS=: read -r file line text; do
        echo "${file#"$root"/}:$line: $text  <- only fsw/$DDS_FOLDER talks to DDS"
        violations=$((violations + 1))
      done < <(grep -rnE --include='*.cpp' --include='*.hpp' --include='*.h' --include='*.c' \
                 '^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"](dds/|idl/)' "$dir" 2>/dev/null)
      while IFS=: read -r file line text; do
        target=$(sed -E 's/.*visnav\/'"$DDS_FOLDER"'\/([A-Za-z0-9_.]+).*/\1/' <<<"$text")
        [[ -f $root/fsw/$DDS_FOLDER/$DDS_INCLUDE/visnav/$DDS_FOLDER/$target ]] || continue
        echo "${file#"$root"/}:$line: $text  <- a DDS-level header (fsw/$DDS_FOLDER/$DDS_INCLUDE): only fsw/$DDS_FOLDER, ground tools and tests"
        violations=$((violations + 1))
      done < <(grep -rnE --include='*.cpp' --include='*.hpp' --include='*.h' --include='*.c' \
                 '^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]visnav/'"$DDS_FOLDER"'/' "$dir" 2>/dev/null)
      if [[ -f $dir/CMakeLists.txt ]]; then
        while IFS=: read -r line text; do
          echo "${dir#"$root"/}/CMakeLists.txt:$line: $text  <- only fsw/$DDS_FOLDER links DDS (others get it PRIVATE, through it)"
          violations=$((violations + 1))
        done < <(grep -nE 'CycloneDDS|visnav_'"$DDS_FOLDER"'_dds|'"$DDS_INCLUDE" "$dir/CMakeLists.txt")
      fi
    else
      # The public (flight) interface of telemetry is DDS-free, also through its own DDS-level headers.
      while IFS=: read -r file line text; do
        target=$(sed -E 's/.*[<"]([^>"]+)[>"].*/\1/' <<<"$text")
        if [[ $target == dds/* || $target == idl/* || -f $dir/$DDS_INCLUDE/$target ]]; then
          echo "${file#"$root"/}:$line: $text  <- fsw/$DDS_FOLDER/include is the DDS-free interface (DDS goes in $DDS_INCLUDE)"
          violations=$((violations + 1))
        fi
      done < <(grep -rnE --include='*.hpp' --include='*.h' '^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]' \
                 "$dir/include" 2>/dev/null)
    fi
    # Another folder's include directory added by path in CMake.
    if [[ -f $dir/CMakeLists.txt ]]; then
      while IFS=: read -r line text; do
        target=$(sed -E 's/.*(fsw|drivers)\/([A-Za-z0-9_]+)\/include.*/\2/' <<<"$text")
        [[ $target == "$folder" || $allowed == *" $target "* ]] && continue
        echo "${dir#"$root"/}/CMakeLists.txt:$line: $text  <- $folder may use only:${allowed% }"
        violations=$((violations + 1))
      done < <(grep -nE '(fsw|drivers)/[A-Za-z0-9_]+/include' "$dir/CMakeLists.txt")
    fi
  done
  if ((violations > 0)); then
    echo "check-deps: $violations include(s) against the dependency direction (README.md, \"The house\")"
    return 1
  fi
  echo "check-deps: ${#folders[@]} folders, every include goes down the dependency graph"
  return 0
}

# Expects `check_tree $1` to exit with $2 and, when given, its output to contain $3.
expect() {
  local root=$1 want=$2 needle=${3:-} out status
  out=$(check_tree "$root" 2>&1)
  status=$?
  if [[ $status -ne $want ]]; then
    echo "self-test FAILED: expected exit $want, got $status${needle:+ (case: $needle)}"
    echo "$out"
    return 1
  fi
  if [[ -n $needle && $out != *"$needle"* ]]; then
    echo "self-test FAILED: output does not name '$needle':"
    echo "$out"
    return 1
  fi
  echo "self-test ok: exit $status${needle:+, names $needle}"
}

self_test() {
  local tmp failed=0
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' RETURN
  # A clean miniature of the house passes.
  mkdir -p "$tmp/fsw/core/include/visnav/core" "$tmp/fsw/farrange/include/visnav/farrange" \
           "$tmp/fsw/navigation/include/visnav/navigation" "$tmp/fsw/app/src" "$tmp/drivers/camera/src"
  echo '#pragma once' >"$tmp/fsw/core/include/visnav/core/stage_interfaces.hpp"
  printf '#pragma once\n#include "visnav/core/stage_interfaces.hpp"\n' \
    >"$tmp/fsw/farrange/include/visnav/farrange/nav_conversion.hpp"
  printf '#pragma once\n#include "visnav/farrange/nav_conversion.hpp"\n#include "visnav/navigation/x.hpp"\n' \
    >"$tmp/fsw/navigation/include/visnav/navigation/nav_solution.hpp"
  printf '#include "visnav/navigation/nav_solution.hpp"\n#include "visnav/camera/camera_source.hpp"\n' \
    >"$tmp/fsw/app/src/daemon.cpp"
  printf '#include <cstdint>\n#include "visnav/core/frame.hpp"\n' >"$tmp/drivers/camera/src/camera.cpp"
  expect "$tmp" 0 || failed=1
  # Upward include: far range reaching for navigation (what acquisition and far range used to do).
  printf '\n  #include "visnav/navigation/nav_solution.hpp"  // the contract\n' \
    >>"$tmp/fsw/farrange/include/visnav/farrange/nav_conversion.hpp"
  expect "$tmp" 1 "fsw/farrange/include/visnav/farrange/nav_conversion.hpp:4:" || failed=1
  printf '#pragma once\n#include "visnav/core/stage_interfaces.hpp"\n' \
    >"$tmp/fsw/farrange/include/visnav/farrange/nav_conversion.hpp"
  expect "$tmp" 0 || failed=1
  # A driver including a stage library, and core including anything.
  echo '#include "visnav/geometry/pose.hpp"' >>"$tmp/drivers/camera/src/camera.cpp"
  expect "$tmp" 1 "drivers/camera/src/camera.cpp:3:" || failed=1
  sed -i '$d' "$tmp/drivers/camera/src/camera.cpp"
  echo '#include <visnav/app/daemon.hpp>' >"$tmp/fsw/core/include/visnav/core/bad.hpp"
  expect "$tmp" 1 "fsw/core/include/visnav/core/bad.hpp:1:" || failed=1
  rm "$tmp/fsw/core/include/visnav/core/bad.hpp"
  # DDS outside telemetry: directly, through a DDS-level telemetry header, or linked in CMake; and a DDS
  # header in telemetry's public interface.
  mkdir -p "$tmp/fsw/telemetry/include/visnav/telemetry" "$tmp/fsw/telemetry/include-dds/visnav/telemetry"
  printf '#pragma once\n#include <cstdint>\n' >"$tmp/fsw/telemetry/include/visnav/telemetry/telemetry_writer.hpp"
  printf '#pragma once\n#include <dds/dds.h>\n' >"$tmp/fsw/telemetry/include-dds/visnav/telemetry/dds_topics.hpp"
  echo '#include "visnav/telemetry/telemetry_writer.hpp"' >>"$tmp/fsw/app/src/daemon.cpp"
  expect "$tmp" 0 || failed=1
  echo '#include <dds/dds.h>' >>"$tmp/fsw/app/src/daemon.cpp"
  expect "$tmp" 1 "fsw/app/src/daemon.cpp:4:" || failed=1
  sed -i '$d' "$tmp/fsw/app/src/daemon.cpp"
  echo '#include "visnav/telemetry/dds_topics.hpp"' >>"$tmp/fsw/app/src/daemon.cpp"
  expect "$tmp" 1 "fsw/app/src/daemon.cpp:4:" || failed=1
  sed -i '$d' "$tmp/fsw/app/src/daemon.cpp"
  echo 'target_link_libraries(visnav_app PUBLIC CycloneDDS::ddsc)' >"$tmp/fsw/app/CMakeLists.txt"
  expect "$tmp" 1 "fsw/app/CMakeLists.txt:1:" || failed=1
  echo 'target_link_libraries(visnav_app PUBLIC visnav_telemetry_dds)' >"$tmp/fsw/app/CMakeLists.txt"
  expect "$tmp" 1 "fsw/app/CMakeLists.txt:1:" || failed=1
  rm "$tmp/fsw/app/CMakeLists.txt"
  echo '#include "visnav/telemetry/dds_topics.hpp"' >>"$tmp/fsw/telemetry/include/visnav/telemetry/telemetry_writer.hpp"
  expect "$tmp" 1 "fsw/telemetry/include/visnav/telemetry/telemetry_writer.hpp:3:" || failed=1
  sed -i '$d' "$tmp/fsw/telemetry/include/visnav/telemetry/telemetry_writer.hpp"
  echo '#include "idl/visnav.h"' >>"$tmp/fsw/telemetry/include/visnav/telemetry/telemetry_writer.hpp"
  expect "$tmp" 1 "fsw/telemetry/include/visnav/telemetry/telemetry_writer.hpp:3:" || failed=1
  sed -i '$d' "$tmp/fsw/telemetry/include/visnav/telemetry/telemetry_writer.hpp"
  expect "$tmp" 0 || failed=1
  # The CMake way round: another folder's include directory added by path.
  echo 'target_include_directories(x PUBLIC ${PROJECT_SOURCE_DIR}/fsw/navigation/include)' \
    >"$tmp/fsw/farrange/CMakeLists.txt"
  expect "$tmp" 1 "fsw/farrange/CMakeLists.txt:1:" || failed=1
  rm "$tmp/fsw/farrange/CMakeLists.txt"
  # A folder nobody put in the graph.
  mkdir -p "$tmp/fsw/newstage/src"
  expect "$tmp" 1 "fsw/newstage: folder not in the dependency graph" || failed=1
  rmdir "$tmp/fsw/newstage/src" "$tmp/fsw/newstage"
  expect "$tmp" 0 || failed=1
  # A cycle in the graph itself is refused.
  DIRECT[core]="app"
  ALLOWED=()
  expect "$tmp" 2 "has a cycle" || failed=1
  if ((failed)); then
    echo "check-deps: self-test FAILED"
    return 1
  fi
  echo "check-deps: self-test passed (every planted violation was caught)"
}

root="$(cd "$(dirname "$0")/.." && pwd)"
case ${1:-} in
  --self-test) self_test; exit $? ;;
  --root) root=${2:?usage: scripts/check-deps.sh [--root DIR | --self-test]} ;;
  "") ;;
  *) echo "usage: scripts/check-deps.sh [--root DIR | --self-test]" >&2; exit 2 ;;
esac
check_tree "$root"
