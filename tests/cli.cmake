# Command-line tests (maintained with cli/): the built `flaplag` binary is run as a user would
# run it, the option vocabulary of cli/ is checked directly, and the parameter table /
# validation that the command line relies on.

# A test that runs the built flaplag binary (FLAPLAG_EXE), built before it.  Its tests carry the
# label runs_flaplag, and the target cli_tests builds them all: the sanitizer pass of .ci/run
# builds and runs these.  The driver itself is built plain, at -O0 and without sanitizer
# instrumentation: it starts the binary and reads what it wrote, so what a sanitizer must watch
# is the binary and the libraries the driver links (compiled with the build's flags), and
# instrumenting and optimizing the drivers' GoogleTest and JSON code was 40 % of that pass's
# build for nothing.  A driver that makes or drops the library's Eigen objects itself (an
# Analysis, its results) says LIBRARY and keeps the build's flags: under AddressSanitizer Eigen
# allocates its own way, so a plain driver would free with another rule than the library used.
set(FLAPLAG_CLI_DRIVER_OPTIONS -O0 -fno-sanitize=all)
function(flaplag_cli_test name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "LIBRARY" "" "UNITS;LIBRARIES")
  flaplag_test(${name} LABEL runs_flaplag UNITS ${arg_UNITS} LIBRARIES ${arg_LIBRARIES})
  if(NOT arg_LIBRARY)
    target_compile_options(${name} PRIVATE ${FLAPLAG_CLI_DRIVER_OPTIONS})
  endif()
  if(CMAKE_CXX_FLAGS MATCHES "-fsanitize=[^ ]*address")
    target_compile_definitions(${name} PRIVATE FLAPLAG_EXE_ASAN=1)  # tests/process.h
  endif()
  set_property(GLOBAL APPEND PROPERTY FLAPLAG_CLI_TESTS ${name})
  target_compile_definitions(${name} PRIVATE FLAPLAG_EXE="$<TARGET_FILE:flaplag>")
  add_dependencies(${name} flaplag)
endfunction()

# The units: cli (the vocabulary of cli/ and the output contract); cli_fuzz (generated command
# lines, FLAPLAG_FUZZ_VECTORS, default 1000); cli_studies (study, map, run of case files,
# --plot, response, simulate); cli_security (what received files and typed texts can make
# flaplag do: gnuplot, symbolic links, output paths, descriptors, signals); cli_files (JSON cases
# never name outputs, bounded nesting and size, keys once per case, merge's checks of a part
# against its case); cli_blade (blade tables and imported mode shapes); file_fuzz (generated and
# mutated case files and results to run, plot and merge, FLAPLAG_FILE_FUZZ_VECTORS per kind);
# cli_honest (statuses that rest on trims, validity, resolution); cli_limits (--memory-limit:
# large runs refused before they allocate); cli_spec (--spec FILE.toml, a model derived at run
# time; needs GiNaC); report (flaplag report and --report, each example's page in headless
# Chromium).
set(flaplag_cli_units cli_test cli_fuzz_test cli_studies_test cli_security_test cli_files_test
                      cli_blade_test file_fuzz_test cli_honest_test cli_limits_test report_test)
if(TARGET flaplag_derive)
  list(APPEND flaplag_cli_units cli_spec_test)
endif()
flaplag_cli_test(cli_driver_tests UNITS ${flaplag_cli_units}
                 LIBRARIES flaplag_cli nlohmann_json::nlohmann_json)
target_compile_definitions(cli_driver_tests PRIVATE
  FLAPLAG_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
  FLAPLAG_SPEC_DIR="${PROJECT_SOURCE_DIR}/generator/orderings")

# --inflow: fixed controls at the momentum inflow, against the library at eq 2.25's lambda; and
# cli_equilibrium: the q° of --periodic-linearization documents against the library's.
flaplag_cli_test(cli_inflow_test LIBRARY UNITS cli_inflow_test cli_equilibrium_test
                 LIBRARIES flaplag_analysis nlohmann_json::nlohmann_json)

# The parameter table and validation the command line relies on; docs/json.md is fresh
# (refresh-docs), and the JSON writer of the field tables.
flaplag_test(cli_library_tests UNITS parameters_test json_docs_test
             LIBRARIES flaplag_cli nlohmann_json::nlohmann_json)
target_compile_definitions(cli_library_tests PRIVATE
  FLAPLAG_JSON_DOCS="${PROJECT_SOURCE_DIR}/docs/json.md")

# `cmake --build . --target cli_tests`: the flaplag binary and every test that runs it.
get_property(flaplag_cli_tests GLOBAL PROPERTY FLAPLAG_CLI_TESTS)
add_custom_target(cli_tests DEPENDS ${flaplag_cli_tests})
