# Every installed binary answers --help (usage on stdout, exit 0) and --version ("NAME VERSION" on stdout,
# exit 0), and a usage error still goes to stderr with exit 2. Invoked as:
#   cmake -DBINARIES=<exe;exe;...> -DVERSION=x.y.z -P help_version.cmake
set(errors "")
foreach(binary IN LISTS BINARIES)
  get_filename_component(name ${binary} NAME)
  execute_process(COMMAND ${binary} --help RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  TIMEOUT 30)
  if(NOT rc EQUAL 0 OR out STREQUAL "" OR NOT err STREQUAL "" OR NOT out MATCHES "usage: ${name}")
    string(APPEND errors "${name} --help: exit ${rc}, stdout '${out}', stderr '${err}'\n")
  endif()
  execute_process(COMMAND ${binary} --version RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  TIMEOUT 30)
  if(NOT rc EQUAL 0 OR NOT out STREQUAL "${name} ${VERSION}\n" OR NOT err STREQUAL "")
    string(APPEND errors "${name} --version: exit ${rc}, stdout '${out}', stderr '${err}'\n")
  endif()
  execute_process(COMMAND ${binary} --no-such-option RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err TIMEOUT 30)
  if(NOT rc EQUAL 2 OR err STREQUAL "")
    string(APPEND errors "${name} --no-such-option: exit ${rc} (expected 2), stderr '${err}'\n")
  endif()
endforeach()
list(LENGTH BINARIES n)
if(errors)
  message(FATAL_ERROR "${errors}")
endif()
message(STATUS "${n} binaries: --help and --version exit 0 on stdout, a bad option exits 2")
