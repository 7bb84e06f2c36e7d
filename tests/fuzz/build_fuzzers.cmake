# build_fuzzers.cmake - configures and builds the libFuzzer project
# (libfuzzer/CMakeLists.txt) with clang; the fuzz.build test runs it so that
# the project's own build keeps its compiler.
#   cmake -DSOURCE=<tests/fuzz/libfuzzer> -DBINARY=<folder> -DCC=<clang> -DCXX=<clang++>
#         -DARBOR_BUILD=<the Arbor build> -DJOBS=<n> -P build_fuzzers.cmake
foreach(var SOURCE BINARY CC CXX ARBOR_BUILD JOBS)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "build_fuzzers.cmake: -D${var}=... is missing")
  endif()
endforeach()
execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${SOURCE} -B ${BINARY} -DCMAKE_C_COMPILER=${CC} -DCMAKE_CXX_COMPILER=${CXX}
    -DARBOR_BUILD=${ARBOR_BUILD}
  COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BINARY} -j ${JOBS} COMMAND_ERROR_IS_FATAL ANY)
