# Configures and builds the consumer project against an install tree and runs both programs.
#   cmake -DPREFIX=<install prefix> -DSOURCE=<tests/consumer> -DBINARY=<build dir>
#         [-DGENERATOR=...] [-DCXX=<compiler>] [-DCXX_FLAGS=...] [-DLINKER_FLAGS=...]
#         -P run.cmake
foreach(v PREFIX SOURCE BINARY)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "run.cmake: -D${v}=... is required")
  endif()
endforeach()

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    string(REPLACE ";" " " cmd "${ARGN}")
    message(FATAL_ERROR "failed (${rc}): ${cmd}")
  endif()
endfunction()

file(REMOVE_RECURSE ${BINARY})
set(generator_args "")
if(GENERATOR)
  set(generator_args -G ${GENERATOR})
endif()
set(compiler_args "")
if(CXX)
  set(compiler_args -DCMAKE_CXX_COMPILER=${CXX})
endif()
# Only the install tree: the pkg-config search path too, and the consumer must not see the
# packages only flaplag's build and command line need.
file(GLOB pc_dirs LIST_DIRECTORIES true ${PREFIX}/lib*/pkgconfig ${PREFIX}/lib/*/pkgconfig)
string(REPLACE ";" ":" pc_path "${pc_dirs}")
set(ENV{PKG_CONFIG_PATH} "${pc_path}")
run(${CMAKE_COMMAND} -S ${SOURCE} -B ${BINARY} ${generator_args} ${compiler_args}
    "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${LINKER_FLAGS}"
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${PREFIX}
    -DCMAKE_DISABLE_FIND_PACKAGE_CLI11=ON -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON
    -DCMAKE_DISABLE_FIND_PACKAGE_tomlplusplus=ON)
run(${CMAKE_COMMAND} --build ${BINARY} -j2)
run(${BINARY}/consumer_cmake)
run(${BINARY}/consumer_pkgconfig)
