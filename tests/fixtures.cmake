# Test code compiled once, shared by the test executables and the benches (included by the
# top-level CMakeLists.txt when either is built).  It is compiled at -O1 in an optimized build:
# it is test code, and GCC's x86-64 code gives the same IEEE results at every -O level (at -O0,
# as the test drivers are, it compiles in 5.8 s of CPU against 6.7 s, and the systems the tests
# sample from it are built slower).
#
# flaplag_test_fixtures: the periodic systems of periodic_fixtures.h and the dense helpers the
# numerics tests check with (an inverse and an operator norm written without Eigen's
# decompositions, which cost more compile time than the rest of the fixtures).
add_library(flaplag_test_fixtures STATIC ${CMAKE_CURRENT_LIST_DIR}/periodic_fixtures.cc)
target_include_directories(flaplag_test_fixtures PUBLIC ${CMAKE_CURRENT_LIST_DIR})
target_link_libraries(flaplag_test_fixtures PUBLIC flaplag_numerics)
flaplag_warnings(flaplag_test_fixtures)
if(CMAKE_BUILD_TYPE MATCHES "^(Release|RelWithDebInfo|MinSizeRel)$")
  target_compile_options(flaplag_test_fixtures PRIVATE -O1)
endif()
