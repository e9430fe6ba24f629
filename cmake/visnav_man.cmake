# Man pages (man1) of every binary visnav_add_tool installs, made at build time by help2man from the
# binary's own --help and --version (so they never drift from the code), gzip -9n (reproducible), installed
# to share/man/man1. Without help2man (scripts/install-deps.sh installs it) the build goes on without them.
# A cross build runs the binaries through CMAKE_CROSSCOMPILING_EMULATOR (qemu-aarch64).
set(VISNAV_MAN_visnavd "the visnav flight program (camera, navigation pipeline, DDS telemetry)")
set(VISNAV_MAN_visnav-replay "run the visnav flight pipeline over a recorded image sequence")
set(VISNAV_MAN_visnav-synth "render a synthetic image sequence with truth from a scenario")
set(VISNAV_MAN_visnav-eval "score a visnav-replay CSV against a sequence's truth")
set(VISNAV_MAN_visnav-params "print the visnav parameter reference or validate a config file")
set(VISNAV_MAN_visnav-monitor "live view and CSV recording of visnavd's DDS telemetry")
set(VISNAV_MAN_visnav-command "send a mode command to visnavd and wait for its acknowledgment")
set(VISNAV_MAN_visnav-calibrate-gamma "calibrate the far-range distance constant from frames at known distance")
set(VISNAV_MAN_visnav-far-eval "evaluate the far-range estimator on a sequence with truth")
set(VISNAV_MAN_visnav-jitter "measure the cyclic executive's release jitter on the real clock")
set(VISNAV_MAN_visnav-csvdiff "compare two CSV files numerically, cell by cell")
set(VISNAV_MAN_visnav-campaign "seeded Monte Carlo campaign through the whole visnav pipeline")
set(VISNAV_MAN_visnav-edge-score "score how well projected model edges lie on the image gradient")

find_program(VISNAV_HELP2MAN help2man)
find_program(VISNAV_GZIP gzip)
get_property(_visnav_man_tools GLOBAL PROPERTY VISNAV_TOOLS)
set(VISNAV_MAN_PAGES OFF)
if(NOT VISNAV_HELP2MAN OR NOT VISNAV_GZIP)
  message(STATUS "help2man or gzip not found: no man pages (scripts/install-deps.sh installs help2man)")
elseif(CMAKE_CROSSCOMPILING AND NOT CMAKE_CROSSCOMPILING_EMULATOR)
  message(STATUS "cross build without CMAKE_CROSSCOMPILING_EMULATOR: no man pages (help2man runs the binaries)")
else()
  set(_visnav_man_dir ${CMAKE_BINARY_DIR}/man)
  file(MAKE_DIRECTORY ${_visnav_man_dir})
  set(_visnav_man_pages "")
  foreach(tool IN LISTS _visnav_man_tools)
    if(NOT DEFINED VISNAV_MAN_${tool})
      message(FATAL_ERROR "cmake/visnav_man.cmake: add the one-line description VISNAV_MAN_${tool}")
    endif()
    set(program $<TARGET_FILE:${tool}>)
    if(CMAKE_CROSSCOMPILING)  # help2man runs one path: a wrapper that starts the binary in the emulator
      set(program ${_visnav_man_dir}/run-${tool})
      file(GENERATE OUTPUT ${program} CONTENT "#!/bin/sh\nexec ${CMAKE_CROSSCOMPILING_EMULATOR} $<TARGET_FILE:${tool}> \"$@\"\n"
           FILE_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE WORLD_READ WORLD_EXECUTE)
    endif()
    set(page ${_visnav_man_dir}/${tool}.1)
    add_custom_command(
      OUTPUT ${page}.gz
      COMMAND ${VISNAV_HELP2MAN} --no-info --section=1 "--name=${VISNAV_MAN_${tool}}" --output=${page} ${program}
      COMMAND ${VISNAV_GZIP} -9nf ${page}
      DEPENDS ${tool}
      COMMENT "man page ${tool}.1.gz (help2man)"
      VERBATIM)
    list(APPEND _visnav_man_pages ${page}.gz)
  endforeach()
  add_custom_target(visnav_man_pages ALL DEPENDS ${_visnav_man_pages})
  set(VISNAV_MAN_PAGES ON)
  install(FILES ${_visnav_man_pages} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
endif()
