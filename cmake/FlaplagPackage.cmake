# The installed C++ package: a CMake package (find_package(flaplag) -> flaplag::flaplag), a
# pkg-config file, and the `flaplag` command.  The library targets and their headers are
# installed by runtime/CMakeLists.txt into the export set flaplagTargets; this file writes the
# package files around it.  Included from the top-level CMakeLists.txt after runtime/ and cli/.
include(CMakePackageConfigHelpers)

set(FLAPLAG_CMAKE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/flaplag
    CACHE STRING "Where the CMake package files are installed (relative to the prefix)")
mark_as_advanced(FLAPLAG_CMAKE_INSTALL_DIR)

install(EXPORT flaplagTargets
        NAMESPACE flaplag::
        DESTINATION ${FLAPLAG_CMAKE_INSTALL_DIR}
        COMPONENT devel)

configure_package_config_file(
  ${PROJECT_SOURCE_DIR}/cmake/flaplagConfig.cmake.in
  ${PROJECT_BINARY_DIR}/package/flaplagConfig.cmake
  INSTALL_DESTINATION ${FLAPLAG_CMAKE_INSTALL_DIR})
# 0.x: a minor version may change the API.
write_basic_package_version_file(
  ${PROJECT_BINARY_DIR}/package/flaplagConfigVersion.cmake
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/package/flaplagConfig.cmake
              ${PROJECT_BINARY_DIR}/package/flaplagConfigVersion.cmake
        DESTINATION ${FLAPLAG_CMAKE_INSTALL_DIR}
        COMPONENT devel)

# pkg-config: the static archives in link order (each before the ones it uses).
set(FLAPLAG_PC_LIBS "")
foreach(lib flaplag_analysis flaplag_rotor flaplag_blade flaplag_models flaplag_numerics
            flaplag_core)
  string(APPEND FLAPLAG_PC_LIBS " -l${lib}")
endforeach()
string(STRIP "${FLAPLAG_PC_LIBS}" FLAPLAG_PC_LIBS)
# The prefix relative to <libdir>/pkgconfig, so that the file stays right under any
# `cmake --install --prefix`.
file(RELATIVE_PATH FLAPLAG_PC_PREFIX_FROM_PCDIR "/prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig"
     "/prefix")
string(REGEX REPLACE "/$" "" FLAPLAG_PC_PREFIX_FROM_PCDIR "${FLAPLAG_PC_PREFIX_FROM_PCDIR}")
configure_file(${PROJECT_SOURCE_DIR}/cmake/flaplag.pc.in ${PROJECT_BINARY_DIR}/package/flaplag.pc
               @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/package/flaplag.pc
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig
        COMPONENT devel)

install(TARGETS flaplag RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT cli)
