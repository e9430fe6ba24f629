# Install layout (FHS, prefix /usr in the packages) and the Debian packages (CPack DEB) for amd64 and arm64.
# Included last from the top-level CMakeLists.txt. Executables install themselves (visnav_add_tool);
# this file adds the data, the systemd unit(s), the ground-tool interface, and the package description.
#   bin/                          daemon and tools (visnav_add_tool)
#   share/visnav/config/          default config, parameter reference, Cyclone DDS configs, cameras, models,
#                                 scenarios (everything under config/ except systemd units)
#   lib/systemd/system/           every systemd unit under config/ (*.service, *.socket, *.timer)
#   lib/sysusers.d/visnav.conf    the system user visnavd runs as (config/visnav.sysusers)
#   share/man/man1/               a man page per binary, help2man from its --help (cmake/visnav_man.cmake)
#   share/doc/visnav/             README.md, copyright, changelog.gz (Debian: a native package's name)
#   /etc/visnav/                  the service's config (visnavd.toml: the synthetic approach, looping) and
#                                 Cyclone DDS config (cyclonedds.xml: the loopback one), Debian conffiles
# and in the package visnav-dev (install component "dev"), for ground clients of the telemetry:
#   include/visnav/idl/           visnav.idl and the header idlc makes from it (no build-machine paths)
#   lib/<multiarch>/libvisnav-idl.a   the types' DDS topic descriptors (idl/CMakeLists.txt)
#   lib/<multiarch>/pkgconfig/visnav-idl.pc, lib/<multiarch>/cmake/visnav-idl/   pkg-config and CMake package
#   share/visnav/ros2/visnav_msgs/  the ROS 2 message package of the same types (msg/*.msg, package.xml,
#                                 CMakeLists.txt: copy into a colcon workspace; idl/README.md)
# and visnav-dbgsym: the binaries' debug info (.build-id/xx/yyyy.debug), split off by CPack.
# The flight libraries are static and linked into the executables.
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
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
include(${CMAKE_CURRENT_LIST_DIR}/visnav_man.cmake)

# visnav-dev: what a ground client needs to read and write the telemetry with Cyclone DDS (C): the IDL, its
# header and the descriptors (libvisnav-idl.a), found by pkg-config (visnav-idl) or CMake
# (find_package(visnav-idl), target visnav::visnav_idl_types). Libraries go to Debian's multiarch folder.
if(CMAKE_LIBRARY_ARCHITECTURE)
  set(VISNAV_INSTALL_LIBDIR lib/${CMAKE_LIBRARY_ARCHITECTURE})
else()
  set(VISNAV_INSTALL_LIBDIR ${CMAKE_INSTALL_LIBDIR})
endif()
install(TARGETS visnav_idl_types EXPORT visnav-idl-targets
        ARCHIVE DESTINATION ${VISNAV_INSTALL_LIBDIR} COMPONENT dev
        PUBLIC_HEADER DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/visnav/idl COMPONENT dev)
install(FILES ${PROJECT_SOURCE_DIR}/idl/visnav.idl DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/visnav/idl COMPONENT dev)
# The ROS 2 .msg files with their package files, for `naming = "ros2"` subscribers (idl/ros2/visnav_msgs).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/idl/ros2/visnav_msgs DESTINATION ${CMAKE_INSTALL_DATADIR}/visnav/ros2
        COMPONENT dev)
install(EXPORT visnav-idl-targets NAMESPACE visnav:: DESTINATION ${VISNAV_INSTALL_LIBDIR}/cmake/visnav-idl
        COMPONENT dev)
include(CMakePackageConfigHelpers)
file(WRITE ${CMAKE_BINARY_DIR}/deb/visnav-idl-config.cmake
     "# visnav-idl: C types and DDS topic descriptors of visnav.idl (package visnav-dev)\n"
     "include(CMakeFindDependencyMacro)\nfind_dependency(CycloneDDS 0.10)\n"
     "include(\${CMAKE_CURRENT_LIST_DIR}/visnav-idl-targets.cmake)\n")
write_basic_package_version_file(${CMAKE_BINARY_DIR}/deb/visnav-idl-config-version.cmake
                                 COMPATIBILITY SameMinorVersion)  # 0.x: a minor version may change the types
install(FILES ${CMAKE_BINARY_DIR}/deb/visnav-idl-config.cmake ${CMAKE_BINARY_DIR}/deb/visnav-idl-config-version.cmake
        DESTINATION ${VISNAV_INSTALL_LIBDIR}/cmake/visnav-idl COMPONENT dev)
# The .pc names the package's own prefix (/usr), never the build's; a staged copy is used with
# --define-variable=prefix=ROOT/usr (tests/package/test_dev_client.sh).
set(VISNAV_PC_LIBDIR ${VISNAV_INSTALL_LIBDIR})
configure_file(${CMAKE_CURRENT_LIST_DIR}/deb/visnav-idl.pc.in ${CMAKE_BINARY_DIR}/deb/visnav-idl.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/deb/visnav-idl.pc DESTINATION ${VISNAV_INSTALL_LIBDIR}/pkgconfig COMPONENT dev)
# The C ABI library libvisnav.so.N (fsw/capi, include/visnav/visnav.h) installs itself: the shared library in
# component "capi", its header and the libvisnav.so namelink in "capi_dev". Here it becomes the package
# libvisnav<N> (Debian policy 8.1: a shared library's package is named after its soname; lintian
# package-name-doesnt-match-sonames otherwise), with a shlibs file and the ldconfig trigger; "capi_dev" goes
# into visnav-dev, which then depends on that exact libvisnav<N>. A tree without the target packages as before.
set(VISNAV_CAPI_TARGET visnav CACHE STRING "Target of the C ABI shared library (libvisnav.so.N), if any")
set(VISNAV_CAPI_PACKAGE "")
if(TARGET ${VISNAV_CAPI_TARGET})
  get_target_property(_visnav_capi_type ${VISNAV_CAPI_TARGET} TYPE)
  get_target_property(_visnav_capi_soversion ${VISNAV_CAPI_TARGET} SOVERSION)
  if(_visnav_capi_type STREQUAL "SHARED_LIBRARY" AND _visnav_capi_soversion)
    set(VISNAV_CAPI_PACKAGE libvisnav${_visnav_capi_soversion})
  endif()
endif()

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
install(FILES ${CMAKE_CURRENT_LIST_DIR}/deb/copyright ${CMAKE_BINARY_DIR}/deb/changelog.gz
        DESTINATION ${CMAKE_INSTALL_DATAROOTDIR}/doc/visnav-dev COMPONENT dev)
if(VISNAV_CAPI_PACKAGE)
  install(FILES ${CMAKE_CURRENT_LIST_DIR}/deb/copyright ${CMAKE_BINARY_DIR}/deb/changelog.gz
          DESTINATION ${CMAKE_INSTALL_DATAROOTDIR}/doc/${VISNAV_CAPI_PACKAGE} COMPONENT capi)
endif()
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
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # <package>_<version>_<arch>.deb, <package>-dbgsym_..._<arch>.ddeb
set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE ${VISNAV_DEB_ARCH})
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
# One package per group of install components: "runtime" = component Unspecified (every install() without
# COMPONENT), package visnav; "development" = dev (+ capi_dev), package visnav-dev; "library" = capi, package
# libvisnav<N> (when the C ABI library is built).
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_GROUPING ONE_PER_GROUP)
set(CPACK_COMPONENTS_ALL Unspecified dev)
set(CPACK_COMPONENT_UNSPECIFIED_GROUP runtime)
set(CPACK_COMPONENT_DEV_GROUP development)

# visnav: daemon, tools, config, units, man pages.
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME visnav)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SECTION science)
set(CPACK_DEBIAN_RUNTIME_DESCRIPTION "Monocular vision navigation for spacecraft rendezvous (flight daemon, tools)
Real-time navigation fix on a passive client satellite from one camera:
far-range direction and distance, near-range 6-DOF edge tracking, a Kalman
filter and FDIR, run by the visnavd daemon at 5 Hz with DDS telemetry.
The ground tools replay and score recorded or synthetic sequences, watch the
telemetry and send mode commands.")
# Run-time dependencies from the ELF files (dpkg-shlibdeps: libc6, libstdc++6, libgcc-s1, Cyclone DDS
# libddsc0debian, libtomlplusplus3, zlib1g (the plots' PNG writer, tools/png); libcamera once an installed
# executable links it); works for the arm64 binaries too because the arm64 libraries are installed as
# multiarch packages.
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SHLIBDEPS ON)
# What CPack 3.25 gets wrong in the -dbgsym and library packages is repaired after it made them (the script says
# what and why).
set(CPACK_POST_BUILD_SCRIPTS ${CMAKE_CURRENT_LIST_DIR}/deb/finish_packages.cmake)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_CONTROL_EXTRA ${CMAKE_CURRENT_LIST_DIR}/deb/postinst ${CMAKE_CURRENT_LIST_DIR}/deb/prerm
                                              ${CMAKE_CURRENT_LIST_DIR}/deb/postrm ${CMAKE_CURRENT_LIST_DIR}/deb/conffiles)
# Debug info kept apart: the release preset compiles with -g; CPack's dbgsym step (it only handles files
# `file` calls "not stripped", so CPACK_STRIP_FILES must stay OFF) copies each ELF file's debug info to
# usr/lib/debug/.build-id/<xx>/<rest>.debug in <package>-dbgsym (.ddeb, as Debian's archive names them),
# strips the packaged file (--strip-unneeded) and adds a .gnu_debuglink. gdb finds them by build id.
set(CPACK_STRIP_FILES OFF)
set(CPACK_DEBIAN_RUNTIME_DEBUGINFO_PACKAGE ON)
# The toolchain's binutils (aarch64-linux-gnu-objcopy in the cross build), not whatever `objcopy` is on PATH.
if(CMAKE_OBJCOPY AND CMAKE_READELF)
  set(CPACK_OBJCOPY_EXECUTABLE ${CMAKE_OBJCOPY})
  set(CPACK_READELF_EXECUTABLE ${CMAKE_READELF})
endif()

# visnav-dev: the IDL, header, libvisnav-idl.a, pkg-config and CMake files (no ELF executable: no shlibdeps).
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_NAME visnav-dev)
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_DEPENDS "cyclonedds-dev (>= 0.10)")
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_SHLIBDEPS OFF)
set(CPACK_DEBIAN_DEVELOPMENT_DEBUGINFO_PACKAGE OFF)
set(CPACK_DEBIAN_DEVELOPMENT_DESCRIPTION "visnav telemetry types and C API for clients (headers, libraries)
The IDL of the visnav DDS telemetry (pose, far-range estimate, health, mode
commands), the C header Cyclone DDS idlc makes from it and libvisnav-idl.a
with the topic descriptors, so a C or C++ client subscribes to visnavd's
topics. Found with pkg-config (visnav-idl) or CMake (find_package(visnav-idl)).
The same types as the ROS 2 message package visnav_msgs (.msg files) in
/usr/share/visnav/ros2, to build in a colcon workspace.
With the C API: include/visnav/visnav.h and the libvisnav.so link.")

if(VISNAV_CAPI_PACKAGE)
  list(APPEND CPACK_COMPONENTS_ALL capi capi_dev)
  set(CPACK_COMPONENT_CAPI_GROUP library)
  set(CPACK_COMPONENT_CAPI_DEV_GROUP development)
  set(CPACK_DEBIAN_LIBRARY_PACKAGE_NAME ${VISNAV_CAPI_PACKAGE})
  set(CPACK_DEBIAN_LIBRARY_PACKAGE_SECTION libs)
  set(CPACK_DEBIAN_LIBRARY_DESCRIPTION "visnav navigation pipeline, C API (shared library)
libvisnav runs the visnav vision-navigation pipeline (far range, acquisition,
near-range tracking, Kalman filter, FDIR) behind a stable C ABI, for Octave
or MATLAB MEX files, Simulink S-functions and other languages.")
  set(CPACK_DEBIAN_LIBRARY_PACKAGE_SHLIBDEPS ON)
  # CPack 3.25 reads these only package-wide; the library package is the only one with a shared object.
  set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)
  set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS_POLICY ">=")
  set(CPACK_DEBIAN_LIBRARY_PACKAGE_CONTROL_EXTRA ${CMAKE_CURRENT_LIST_DIR}/deb/triggers)
  set(CPACK_DEBIAN_LIBRARY_DEBUGINFO_PACKAGE ON)
  set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_DEPENDS
      "${VISNAV_CAPI_PACKAGE} (= ${PROJECT_VERSION}), ${CPACK_DEBIAN_DEVELOPMENT_PACKAGE_DEPENDS}")
  # Executables of visnav that link libvisnav.so.N (visnav-closedloop): dpkg-shlibdeps finds the library in the
  # build (it is in another package of this build, with no shlibs file installed yet), the dependency on
  # exactly this build's libvisnav<N> is written here.
  get_target_property(_visnav_capi_dir ${VISNAV_CAPI_TARGET} LIBRARY_OUTPUT_DIRECTORY)
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS ${_visnav_capi_dir})  # CPack 3.25: no per-package variant
  set(CPACK_DEBIAN_RUNTIME_PACKAGE_DEPENDS "${VISNAV_CAPI_PACKAGE} (= ${PROJECT_VERSION})")
endif()
include(CPack)

# The packages' tests run where the shipped packages come from: the release preset (hardened, -g). In the
# debug preset cpack would split and compress the debug info of the ASan binaries (minutes) to check packages
# nobody ships.
if(VISNAV_BUILD_TESTS AND NOT CMAKE_CROSSCOMPILING AND CMAKE_BUILD_TYPE STREQUAL "Release")
  # The amd64 packages: built with cpack, unpacked into scratch roots (dpkg -x, no root needed), contents and
  # control fields checked (tests/package/check_deb.cmake); they stay for the two tests after it.
  add_test(NAME package_deb_contents
           COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${CMAKE_BINARY_DIR} -DARCH=${VISNAV_DEB_ARCH}
                   -DVERSION=${PROJECT_VERSION} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DMAN_PAGES=${VISNAV_MAN_PAGES}
                   -DCAPI_PACKAGE=${VISNAV_CAPI_PACKAGE} -P ${PROJECT_SOURCE_DIR}/tests/package/check_deb.cmake)
  set_tests_properties(package_deb_contents PROPERTIES LABELS package TIMEOUT 600 RUN_SERIAL ON
                                                       FIXTURES_SETUP visnav_debs)
  # A C client built from the unpacked visnav-dev alone receives the packaged visnavd's telemetry.
  add_test(NAME package_dev_client
           COMMAND bash ${PROJECT_SOURCE_DIR}/tests/package/test_dev_client.sh ${CMAKE_BINARY_DIR}/package_test
                   ${PROJECT_SOURCE_DIR})
  # lintian on every package: 0 errors, 0 warnings.
  add_test(NAME package_lintian
           COMMAND bash ${PROJECT_SOURCE_DIR}/tests/package/lintian.sh ${CMAKE_BINARY_DIR}/package_test)
  set_tests_properties(package_dev_client package_lintian PROPERTIES LABELS package TIMEOUT 600
                                                                     FIXTURES_REQUIRED visnav_debs)
endif()
