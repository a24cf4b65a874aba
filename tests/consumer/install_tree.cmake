# A fresh install of a build tree into a prefix (the fixture of the install tests).
#   cmake -DBUILD=<build dir> -DPREFIX=<prefix> -P install_tree.cmake
file(REMOVE_RECURSE ${PREFIX})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD} --prefix ${PREFIX}
                OUTPUT_QUIET RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install ${BUILD} --prefix ${PREFIX} failed (${rc})")
endif()
message(STATUS "installed ${BUILD} into ${PREFIX}")
