# ctest: install this build into a prefix inside the build tree (fixture flaplag_install_tree),
# then build tests/consumer/ against it and run it.  The Python install test (python/) uses the
# same fixture.  Included from the top-level CMakeLists.txt.
set(FLAPLAG_TEST_PREFIX ${PROJECT_BINARY_DIR}/test-install)
add_test(NAME install.tree
         COMMAND ${CMAKE_COMMAND} -DBUILD=${PROJECT_BINARY_DIR} -DPREFIX=${FLAPLAG_TEST_PREFIX}
                 -P ${CMAKE_CURRENT_LIST_DIR}/install_tree.cmake)
set_tests_properties(install.tree PROPERTIES FIXTURES_SETUP flaplag_install_tree)

add_test(NAME consumer.build_and_run
         COMMAND ${CMAKE_COMMAND} -DPREFIX=${FLAPLAG_TEST_PREFIX}
                 -DSOURCE=${CMAKE_CURRENT_LIST_DIR}
                 -DBINARY=${PROJECT_BINARY_DIR}/test-consumer
                 -DGENERATOR=${CMAKE_GENERATOR} -DCXX=${CMAKE_CXX_COMPILER}
                 # the flags the libraries were built with (a sanitizer build needs its runtime)
                 "-DCXX_FLAGS=${CMAKE_CXX_FLAGS}" "-DLINKER_FLAGS=${CMAKE_EXE_LINKER_FLAGS}"
                 -P ${CMAKE_CURRENT_LIST_DIR}/run.cmake)
set_tests_properties(consumer.build_and_run PROPERTIES FIXTURES_REQUIRED flaplag_install_tree
                                                        TIMEOUT 300)
