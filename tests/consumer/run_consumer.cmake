# Installs the build into a temporary prefix, then builds and runs the
# consumer project against it twice: with find_package(udm1 CONFIG) and with
# pkg-config. Variables: BUILD_DIR, SOURCE_DIR, WORK, C_COMPILER.
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(prefix "${WORK}/prefix")

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

run(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}")

# find_package
run(${CMAKE_COMMAND} -S "${SOURCE_DIR}/tests/consumer" -B "${WORK}/cmake-build"
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_C_COMPILER=${C_COMPILER})
run(${CMAKE_COMMAND} --build "${WORK}/cmake-build")
run("${WORK}/cmake-build/consumer_shared")
if(NOT last_output MATCHES "consumer ok")
  message(FATAL_ERROR "consumer_shared printed: ${last_output}")
endif()
run("${WORK}/cmake-build/consumer_static")
set(static_out "${last_output}")

# pkg-config
file(GLOB_RECURSE pcfile "${prefix}/*/udm1.pc")
if(NOT pcfile)
  message(FATAL_ERROR "udm1.pc was not installed under ${prefix}")
endif()
get_filename_component(pcdir "${pcfile}" DIRECTORY)
run(${CMAKE_COMMAND} -E env PKG_CONFIG_PATH=${pcdir} pkg-config --cflags --libs udm1)
string(STRIP "${last_output}" flags)
separate_arguments(flags UNIX_COMMAND "${flags}")
run(${C_COMPILER} "${SOURCE_DIR}/tests/consumer/main.c" -o "${WORK}/consumer_pc" ${flags})
file(GLOB_RECURSE solib "${prefix}/*/libudm1.so.1")
get_filename_component(libdir "${solib}" DIRECTORY)
run(${CMAKE_COMMAND} -E env LD_LIBRARY_PATH=${libdir} "${WORK}/consumer_pc")
if(NOT last_output STREQUAL static_out)
  message(FATAL_ERROR "pkg-config build printed:\n${last_output}\nstatic build printed:\n${static_out}")
endif()
message(STATUS "consumer builds (find_package shared, static; pkg-config) agree:\n${last_output}")
