# Command-line tests (maintained with cli/): the built `flaplag` binary is run as a user would
# run it, the option vocabulary of cli/ is checked directly, and the parameter table /
# validation that the command line relies on.
flaplag_test(parameters_test flaplag_rotor)

flaplag_test(cli_test flaplag_cli nlohmann_json::nlohmann_json)
target_compile_definitions(cli_test PRIVATE FLAPLAG_EXE="$<TARGET_FILE:flaplag>"
                                            FLAPLAG_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
add_dependencies(cli_test flaplag)

# Generated command lines against the output contract (FLAPLAG_FUZZ_VECTORS, default 1000).
flaplag_test(cli_fuzz_test flaplag_cli nlohmann_json::nlohmann_json)
target_compile_definitions(cli_fuzz_test PRIVATE FLAPLAG_EXE="$<TARGET_FILE:flaplag>")
add_dependencies(cli_fuzz_test flaplag)

# study, map, run (case files), --plot, response, simulate (maintained with cli/).
flaplag_test(cli_studies_test nlohmann_json::nlohmann_json)
target_compile_definitions(cli_studies_test PRIVATE FLAPLAG_EXE="$<TARGET_FILE:flaplag>")
add_dependencies(cli_studies_test flaplag)

# The memory limit (--memory-limit): large runs refused before they allocate (maintained with
# cli/ and runtime/analysis limits.h).
flaplag_test(cli_limits_test flaplag_cli nlohmann_json::nlohmann_json)
target_compile_definitions(cli_limits_test PRIVATE FLAPLAG_EXE="$<TARGET_FILE:flaplag>")
add_dependencies(cli_limits_test flaplag)
