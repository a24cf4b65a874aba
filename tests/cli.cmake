# Command-line tests (maintained with cli/): the built `flaplag` binary is run as a user would
# run it, and the parameter table / validation that the command line relies on.
flaplag_test(parameters_test flaplag_rotor)

flaplag_test(cli_test nlohmann_json::nlohmann_json)
target_compile_definitions(cli_test PRIVATE FLAPLAG_EXE="$<TARGET_FILE:flaplag>")
add_dependencies(cli_test flaplag)
