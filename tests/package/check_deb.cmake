# ctest package_deb_contents: builds the Debian package of this build with cpack, unpacks it into a scratch
# root with dpkg-deb -x (no root needed) and checks what an operator relies on: control fields, the
# daemon/tools in usr/bin and runnable, the default config, every systemd unit under config/, the
# ground-tool IDL and its header (self-contained C), the service's /etc/visnav config as conffiles (valid for
# the packaged visnavd), nothing else outside /usr.
# -DBUILD_DIR=... -DARCH=amd64 -DVERSION=x.y.z -DSOURCE_DIR=...
set(work ${BUILD_DIR}/package_test)
file(REMOVE_RECURSE ${work})
file(MAKE_DIRECTORY ${work})
execute_process(COMMAND cpack -G DEB --config ${BUILD_DIR}/CPackConfig.cmake -B ${work}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
set(deb ${work}/visnav_${VERSION}_${ARCH}.deb)
if(NOT rc EQUAL 0 OR NOT EXISTS ${deb})
  message(FATAL_ERROR "cpack failed (${rc}) or ${deb} missing:\n${out}")
endif()

function(control_field name var)
  execute_process(COMMAND dpkg-deb -f ${deb} ${name} OUTPUT_VARIABLE value OUTPUT_STRIP_TRAILING_WHITESPACE
                  RESULT_VARIABLE frc)
  if(NOT frc EQUAL 0)
    message(FATAL_ERROR "dpkg-deb -f ${name} failed")
  endif()
  set(${var} "${value}" PARENT_SCOPE)
endfunction()
control_field(Package package)
control_field(Architecture arch)
control_field(Version version)
control_field(Depends depends)
set(errors "")
if(NOT package STREQUAL "visnav")
  string(APPEND errors "Package is '${package}'\n")
endif()
if(NOT arch STREQUAL ARCH)
  string(APPEND errors "Architecture is '${arch}', expected ${ARCH}\n")
endif()
if(NOT version STREQUAL VERSION)
  string(APPEND errors "Version is '${version}', expected ${VERSION}\n")
endif()
# shlibdeps found the shared libraries the executables link.
foreach(lib libc6 libstdc\\+\\+6 libddsc libtomlplusplus)
  if(NOT depends MATCHES "(${lib})")
    string(APPEND errors "Depends lacks ${lib}: ${depends}\n")
  endif()
endforeach()

set(root ${work}/root)
execute_process(COMMAND dpkg-deb -x ${deb} ${root} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "dpkg-deb -x failed")
endif()
set(expected usr/bin/visnavd usr/bin/visnav-replay usr/bin/visnav-synth usr/bin/visnav-eval usr/bin/visnav-params
             usr/bin/visnav-monitor usr/bin/visnav-command usr/share/visnav/config/visnav.toml
             usr/share/visnav/config/PARAMETERS.md usr/share/visnav/config/cyclonedds-loopback.xml
             usr/share/visnav/config/scenarios/approach_ci.toml usr/include/visnav/idl/visnav.idl
             usr/include/visnav/idl/visnav.h usr/share/doc/visnav/README.md etc/visnav/visnavd.toml
             etc/visnav/cyclonedds.xml usr/share/doc/visnav/copyright usr/share/doc/visnav/changelog.gz
             usr/lib/sysusers.d/visnav.conf)
# A man page per binary when the build had help2man (MAN_PAGES).
if(MAN_PAGES)
  file(GLOB binaries RELATIVE ${root}/usr/bin ${root}/usr/bin/*)
  foreach(binary IN LISTS binaries)
    list(APPEND expected usr/share/man/man1/${binary}.1.gz)
  endforeach()
endif()
file(GLOB units RELATIVE ${SOURCE_DIR}/config ${SOURCE_DIR}/config/*.service ${SOURCE_DIR}/config/*/*.service)
foreach(unit IN LISTS units)
  get_filename_component(unit_name ${unit} NAME)
  list(APPEND expected usr/lib/systemd/system/${unit_name})
endforeach()
foreach(path IN LISTS expected)
  if(NOT EXISTS ${root}/${path})
    string(APPEND errors "missing ${path}\n")
  endif()
endforeach()
file(GLOB_RECURSE all_files RELATIVE ${root} ${root}/*)
foreach(path IN LISTS all_files)
  if(NOT path MATCHES "^usr/" AND NOT path MATCHES "^etc/visnav/")
    string(APPEND errors "outside /usr and /etc/visnav: ${path}\n")
  endif()
  if(path MATCHES "^usr/share/visnav/config/.*\\.service$")
    string(APPEND errors "systemd unit installed as config: ${path}\n")
  endif()
endforeach()

# The packaged tool validates the packaged default config (binaries run from the scratch root).
execute_process(COMMAND ${root}/usr/bin/visnav-params --check ${root}/usr/share/visnav/config/visnav.toml
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0)
  string(APPEND errors "packaged visnav-params --check on the packaged config failed (${rc}): ${out}\n")
endif()
# The ground-tool header compiles on its own against the installed Cyclone DDS headers.
file(WRITE ${work}/idl_header.c "#include \"visnav/idl/visnav.h\"\nint main(void) { return 0; }\n")
execute_process(COMMAND cc -fsyntax-only -Wall -Werror -I${root}/usr/include ${work}/idl_header.c
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0)
  string(APPEND errors "usr/include/visnav/idl/visnav.h does not compile on its own: ${out}\n")
endif()

# /etc/visnav files are conffiles (an operator's edits survive upgrades), and the service's config is valid
# for the packaged daemon (its device path points into /usr/share/visnav, as installed).
execute_process(COMMAND dpkg-deb -e ${deb} ${work}/control RESULT_VARIABLE rc)
if(rc EQUAL 0 AND EXISTS ${work}/control/conffiles)
  file(READ ${work}/control/conffiles conffiles)
else()
  set(conffiles "")
endif()
foreach(conffile /etc/visnav/visnavd.toml /etc/visnav/cyclonedds.xml)
  if(NOT conffiles MATCHES "${conffile}")
    string(APPEND errors "not a conffile: ${conffile}\n")
  endif()
endforeach()
file(READ ${root}/etc/visnav/visnavd.toml service_config)
if(NOT service_config MATCHES "device = \"/usr/share/visnav/config/scenarios/full_approach_ci.toml\"")
  string(APPEND errors "etc/visnav/visnavd.toml does not fly the installed scenario\n")
endif()
if(NOT EXISTS ${root}/usr/share/visnav/config/scenarios/full_approach_ci.toml)
  string(APPEND errors "missing usr/share/visnav/config/scenarios/full_approach_ci.toml\n")
endif()
# --check opens the scenario too, so the copy checked here points into the scratch root instead of /usr.
string(REPLACE "\"/usr/share/visnav/" "\"${root}/usr/share/visnav/" rooted_config "${service_config}")
file(WRITE ${work}/visnavd-rooted.toml "${rooted_config}")
execute_process(COMMAND ${root}/usr/bin/visnavd --check ${work}/visnavd-rooted.toml
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0)
  string(APPEND errors "packaged visnavd --check on etc/visnav/visnavd.toml failed (${rc}): ${out}\n")
endif()
# Maintainer scripts: systemd-sysusers, deb-systemd-helper / deb-systemd-invoke (stop on remove, purge).
foreach(script postinst prerm postrm)
  if(NOT EXISTS ${work}/control/${script})
    string(APPEND errors "no ${script} maintainer script\n")
  endif()
endforeach()
# Stripped executables (lintian: unstripped-binary-or-object).
foreach(path IN LISTS all_files)
  if(path MATCHES "^usr/bin/")
    execute_process(COMMAND readelf -S ${root}/${path} OUTPUT_VARIABLE sections)
    if(sections MATCHES "\\.debug_info|\\.symtab")
      string(APPEND errors "not stripped: ${path}\n")
    endif()
  endif()
endforeach()
list(LENGTH all_files file_count)
if(errors)
  message(FATAL_ERROR "visnav_${VERSION}_${ARCH}.deb (${file_count} files):\n${errors}")
endif()
message(STATUS "visnav_${VERSION}_${ARCH}.deb: ${file_count} files, Depends: ${depends}")
