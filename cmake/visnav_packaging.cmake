# Install layout (FHS, prefix /usr in the packages) and the Debian packages (CPack DEB) for amd64 and arm64.
# Included last from the top-level CMakeLists.txt. Executables install themselves (visnav_add_tool);
# this file adds the data, the systemd unit(s), the ground-tool interface, and the package description.
#   bin/                          daemon and tools (visnav_add_tool)
#   share/visnav/config/          default config, parameter reference, Cyclone DDS configs, cameras, models,
#                                 scenarios (everything under config/ except systemd units)
#   lib/systemd/system/           every systemd unit under config/ (*.service, *.socket, *.timer)
#   lib/sysusers.d/visnav.conf    the system user visnavd runs as (config/visnav.sysusers)
#   share/man/man1/               a man page per binary, help2man from its --help (cmake/visnav_man.cmake)
#   include/visnav/idl/           visnav.idl and the header idlc generates from it (ground tools)
#   share/doc/visnav/             README.md, copyright, changelog.gz (Debian: a native package's name)
#   /etc/visnav/                  the service's config (visnavd.toml: the synthetic approach, looping) and
#                                 Cyclone DDS config (cyclonedds.xml: the loopback one), Debian conffiles
# The libraries are static and linked into the executables: nothing else goes to lib/.
set(VISNAV_UNIT_PATTERNS *.service *.socket *.timer)
set(_visnav_unit_excludes PATTERN *.sysusers EXCLUDE)
set(_visnav_units)
foreach(pattern IN LISTS VISNAV_UNIT_PATTERNS)
  list(APPEND _visnav_unit_excludes PATTERN ${pattern} EXCLUDE)
  file(GLOB_RECURSE _found CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/config/${pattern})
  list(APPEND _visnav_units ${_found})
endforeach()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/config/ DESTINATION ${CMAKE_INSTALL_DATADIR}/visnav/config
        ${_visnav_unit_excludes})
if(_visnav_units)
  install(FILES ${_visnav_units} DESTINATION lib/systemd/system)
endif()
install(FILES ${PROJECT_SOURCE_DIR}/config/visnav.sysusers DESTINATION lib/sysusers.d RENAME visnav.conf)
install(FILES ${PROJECT_SOURCE_DIR}/idl/visnav.idl DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/visnav/idl)
if(TARGET visnav_telemetry)
  install(FILES ${CMAKE_BINARY_DIR}/fsw/telemetry/idl/visnav.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/visnav/idl)
endif()
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
include(${CMAKE_CURRENT_LIST_DIR}/visnav_man.cmake)

# Debian's copyright and changelog (lintian: a version without a revision is a native package, whose
# changelog is changelog.gz). The date is SOURCE_DATE_EPOCH's when set (reproducible builds).
set(VISNAV_DEB_MAINTAINER "visnav maintainers <visnav-maintainers@example.org>"
    CACHE STRING "Maintainer field and changelog signature of the Debian package (Name <mail>)")
string(TIMESTAMP VISNAV_DEB_DATE "%a, %d %b %Y %H:%M:%S +0000" UTC)
configure_file(${CMAKE_CURRENT_LIST_DIR}/deb/changelog.in ${CMAKE_BINARY_DIR}/deb/changelog @ONLY)
add_custom_command(OUTPUT ${CMAKE_BINARY_DIR}/deb/changelog.gz
                   COMMAND gzip -9nc ${CMAKE_BINARY_DIR}/deb/changelog > ${CMAKE_BINARY_DIR}/deb/changelog.gz
                   DEPENDS ${CMAKE_BINARY_DIR}/deb/changelog VERBATIM)
add_custom_target(visnav_deb_changelog ALL DEPENDS ${CMAKE_BINARY_DIR}/deb/changelog.gz)
install(FILES ${CMAKE_CURRENT_LIST_DIR}/deb/copyright ${CMAKE_BINARY_DIR}/deb/changelog.gz
        DESTINATION ${CMAKE_INSTALL_DOCDIR})
# What config/visnavd.service reads. Absolute: /etc whatever the prefix (FHS), so only the package (or a
# root install) writes it.
install(FILES ${CMAKE_CURRENT_LIST_DIR}/deb/etc/visnavd.toml DESTINATION /etc/visnav)
install(FILES ${PROJECT_SOURCE_DIR}/config/cyclonedds-loopback.xml DESTINATION /etc/visnav RENAME cyclonedds.xml)

# Debian package "visnav" for the architecture being built (the cross build makes the arm64 one).
if(CMAKE_SYSTEM_PROCESSOR MATCHES "^(aarch64|arm64)$")
  set(VISNAV_DEB_ARCH arm64)
elseif(CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64|amd64)$")
  set(VISNAV_DEB_ARCH amd64)
else()
  set(VISNAV_DEB_ARCH ${CMAKE_SYSTEM_PROCESSOR})
endif()
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME visnav)
set(CPACK_PACKAGE_VENDOR "visnav")
set(CPACK_PACKAGE_CONTACT "${VISNAV_DEB_MAINTAINER}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Monocular vision navigation for spacecraft rendezvous (flight daemon, tools)")
set(CPACK_PACKAGE_DESCRIPTION "Real-time navigation fix on a passive client satellite from one camera:
far-range direction and distance, near-range 6-DOF edge tracking, a Kalman
filter and FDIR, run by the visnavd daemon at 5 Hz with DDS telemetry.
The ground tools replay and score recorded or synthetic sequences, watch the
telemetry and send mode commands.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # visnav_<version>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE ${VISNAV_DEB_ARCH})
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# Run-time dependencies from the ELF files (dpkg-shlibdeps: libc6, libstdc++6, libgcc-s1, Cyclone DDS
# libddsc0debian, libtomlplusplus3; libcamera once an installed executable links it); works for the arm64
# binaries too because the arm64 libraries are installed as multiarch packages.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS OFF)
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${CMAKE_CURRENT_LIST_DIR}/deb/postinst ${CMAKE_CURRENT_LIST_DIR}/deb/prerm
                                      ${CMAKE_CURRENT_LIST_DIR}/deb/postrm ${CMAKE_CURRENT_LIST_DIR}/deb/conffiles)
# Stripped binaries (lintian: unstripped-binary-or-object). CPACK_DEBIAN_DEBUGINFO_PACKAGE asks for a
# visnav-dbgsym package, but CPack 3.25 makes none for this monolithic (non-component) package, and the
# release preset has no -g: debug info is not yet kept apart (issue 11, open).
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_DEBUGINFO_PACKAGE ON)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
include(CPack)

# The amd64 package: built with cpack, unpacked into a scratch root (dpkg -x, no root needed), contents and
# control fields checked, and the packaged visnav-params validates the packaged default config.
if(VISNAV_BUILD_TESTS AND NOT CMAKE_CROSSCOMPILING)
  add_test(NAME package_deb_contents
           COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${CMAKE_BINARY_DIR} -DARCH=${VISNAV_DEB_ARCH}
                   -DVERSION=${PROJECT_VERSION} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DMAN_PAGES=${VISNAV_MAN_PAGES}
                   -P ${PROJECT_SOURCE_DIR}/tests/package/check_deb.cmake)
  set_tests_properties(package_deb_contents PROPERTIES LABELS package TIMEOUT 600 RUN_SERIAL ON)
endif()
