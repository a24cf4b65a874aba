# The refresh-generated target (generated/CMakeLists.txt): copies the fresh generator output
# into generated/ and removes the orphans, i.e. the *.cc and *.md files there that no spec
# produces any more (tests/generated_golden_test.cpp flags them by the same rule).
#
#   cmake -DFRESH_DIR=<build>/gen -DGENERATED_DIR=<source>/generated -DMODELS=a,b,c -P this-file
cmake_minimum_required(VERSION 3.18)  # policies for -P (IN_LIST)
foreach(var FRESH_DIR GENERATED_DIR MODELS)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "refresh_generated.cmake: ${var} is not set")
  endif()
endforeach()
string(REPLACE "," ";" models "${MODELS}")

set(expected)
foreach(model IN LISTS models)
  list(APPEND expected ${model}.cc ${model}.md)
endforeach()

file(GLOB present RELATIVE ${GENERATED_DIR} ${GENERATED_DIR}/*.cc ${GENERATED_DIR}/*.md)
foreach(file IN LISTS present)
  if(NOT file IN_LIST expected)
    message(STATUS "refresh-generated: removing generated/${file} (no spec produces it)")
    file(REMOVE ${GENERATED_DIR}/${file})
  endif()
endforeach()

foreach(file IN LISTS expected)
  if(NOT EXISTS ${FRESH_DIR}/${file})
    message(FATAL_ERROR "refresh-generated: no fresh ${FRESH_DIR}/${file}")
  endif()
  # by content (file(COPY) would skip a file whose time stamp happens to match)
  configure_file(${FRESH_DIR}/${file} ${GENERATED_DIR}/${file} COPYONLY)
endforeach()
