# Compares the shared library's ABI with a release's ABI description (libabigail's abidiff): only
# additions pass (new functions and variables, fields appended to the descriptors that carry a
# struct_size, as libudm1/abi/udm1.abignore allows). A removed or changed function, variable or type
# fails with abidiff's report. Variables: LIB, BASELINE (the .abi file), HEADERS (the public headers'
# folder), SUPPRESSIONS. The baseline is written by scripts/abi_dump.sh.
find_program(ABIDIFF abidiff)
if(NOT ABIDIFF)
  message(FATAL_ERROR "abidiff not found: install Debian's abigail-tools (./run.sh test does)")
endif()
execute_process(COMMAND "${ABIDIFF}" --suppressions "${SUPPRESSIONS}" --headers-dir2 "${HEADERS}" "${BASELINE}" "${LIB}"
                OUTPUT_VARIABLE report ERROR_VARIABLE report RESULT_VARIABLE rc)
# abidiff's status is a bit set: 1 error, 2 usage error, 4 ABI change, 8 incompatible change
if(NOT rc MATCHES "^[0-9]+$")
  message(FATAL_ERROR "abidiff did not run: ${rc}\n${report}")
endif()
math(EXPR bad "${rc} & 11")
string(REGEX MATCHALL "[1-9][0-9]* (Removed|Changed)" changes "${report}")
if(NOT bad EQUAL 0 OR changes)
  message(FATAL_ERROR "the ABI of ${LIB} is not ${BASELINE}'s plus additions (abidiff exit ${rc}):\n${report}")
endif()
get_filename_component(base "${BASELINE}" NAME)
string(REGEX MATCH "[0-9]+ Added functions" added "${report}")
message(STATUS "ABI: ${base} plus additions only (${added})")
