# Script mode (cmake -P): runs Cyclone DDS idlc on one IDL file and makes the output fit for installing.
#   -DIDLC=/usr/bin/idlc -DIDL=/path/visnav.idl -DOUT=<dir>
# idlc writes the absolute paths of the build machine into what it generates: a "File name:" and a "Source:"
# line in the comment block, and an include guard spelled from the output path
# (DDSC__WORK_MAIN_BUILD_..._VISNAV_H). The installed header (include/visnav/idl/visnav.h, in visnav-dev) gets
# the file names alone and a fixed guard, so it is the same on every build machine and names no build folder.
get_filename_component(stem ${IDL} NAME_WE)
get_filename_component(idl_name ${IDL} NAME)
file(MAKE_DIRECTORY ${OUT})
execute_process(COMMAND ${IDLC} -o ${OUT} ${IDL} RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "idlc ${IDL} failed (${rc}): ${err}")
endif()
string(TOUPPER "VISNAV_IDL_${stem}_H" guard)
foreach(ext h c)
  set(file ${OUT}/${stem}.${ext})
  file(READ ${file} text)
  string(REGEX REPLACE "File name: [^\n]*" "File name: ${stem}.${ext}" text "${text}")
  string(REGEX REPLACE "Source: [^\n]*" "Source: ${idl_name}" text "${text}")
  string(REGEX REPLACE "DDSC_[A-Z0-9_]*_H" "${guard}" text "${text}")
  file(WRITE ${file} "${text}")
endforeach()
