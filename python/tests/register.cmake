# ctest: the pytest suites of the Python module (one test per file), the examples, and an
# import from an install tree.  Included from python/CMakeLists.txt (after the module targets).
set(py_env
    PYTHONPATH=${CMAKE_CURRENT_BINARY_DIR}
    PYTHONDONTWRITEBYTECODE=1
    MPLBACKEND=Agg
    FLAPLAG_CLI=$<TARGET_FILE:flaplag>)
foreach(suite api cli_equality dask documents fields limits keywords options)
  add_test(NAME python.${suite}
           COMMAND ${Python3_EXECUTABLE} -m pytest -q -rs -p no:cacheprovider
                   ${CMAKE_CURRENT_SOURCE_DIR}/tests/test_${suite}.py
           WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/tests)
  set_tests_properties(python.${suite} PROPERTIES ENVIRONMENT "${py_env}" TIMEOUT 120)
endforeach()
# pytest exits 5 when every test of the file was skipped (no dask.distributed): a skip, not a
# failure; the reason is in the output.
set_tests_properties(python.dask PROPERTIES SKIP_RETURN_CODE 5)

# spec="my.toml": a model derived at run time (needs GiNaC, as the generator).
if(TARGET flaplag_derive)
  add_test(NAME python.spec
           COMMAND ${Python3_EXECUTABLE} -m pytest -q -rs -p no:cacheprovider
                   ${CMAKE_CURRENT_SOURCE_DIR}/tests/test_spec.py
           WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/tests)
  set_tests_properties(python.spec PROPERTIES
    ENVIRONMENT "${py_env};FLAPLAG_SPEC_DIR=${PROJECT_SOURCE_DIR}/generator/orderings" TIMEOUT 300)
endif()

# Generated keyword values against the API's error contract (FLAPLAG_PY_FUZZ_VECTORS calls, each
# in a worker process under a memory cap and a time limit).
add_test(NAME python.fuzz_keywords
         COMMAND ${Python3_EXECUTABLE} -m pytest -q -rs -s -p no:cacheprovider
                 ${CMAKE_CURRENT_SOURCE_DIR}/tests/test_fuzz_keywords.py
         WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/tests)
set_tests_properties(python.fuzz_keywords PROPERTIES ENVIRONMENT "${py_env}" TIMEOUT 600)

set(example_dir ${PROJECT_SOURCE_DIR}/examples/python)
set(example_out ${CMAKE_CURRENT_BINARY_DIR}/examples)
file(MAKE_DIRECTORY ${example_out})
add_test(NAME python.example_fig15
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tests/run_example.py
                 ${example_dir}/fig15.py ${example_out}/fig15.png -- -o ${example_out}/fig15.png)
add_test(NAME python.example_stability_map
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tests/run_example.py
                 ${example_dir}/stability_map.py ${example_out}/stability_map.png
                 -- -o ${example_out}/stability_map.png)
add_test(NAME python.example_forward_flight
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tests/run_example.py
                 ${example_dir}/forward_flight.py ${example_out}/forward_flight.png
                 -- -o ${example_out}/forward_flight.png)
add_test(NAME python.example_your_blade
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tests/run_example.py
                 ${example_dir}/your_blade.py ${example_out}/your_blade.png
                 -- -o ${example_out}/your_blade.png)
set_tests_properties(python.example_fig15 python.example_stability_map
                     python.example_forward_flight python.example_your_blade
                     PROPERTIES ENVIRONMENT "${py_env}" TIMEOUT 120)

# `cmake --install` puts the package under <prefix>/${FLAPLAG_PYTHON_INSTALL_DIR}; import it
# from there (fixture of tests/consumer/register.cmake), from a directory with nothing else.
if(DEFINED FLAPLAG_TEST_PREFIX)
  set(install_check_dir ${CMAKE_CURRENT_BINARY_DIR}/install-check)
  file(MAKE_DIRECTORY ${install_check_dir})
  add_test(NAME python.installed
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tests/installed_check.py
                   ${FLAPLAG_TEST_PREFIX}
           WORKING_DIRECTORY ${install_check_dir})
  set_tests_properties(python.installed PROPERTIES
    ENVIRONMENT "PYTHONPATH=${FLAPLAG_TEST_PREFIX}/${FLAPLAG_PYTHON_INSTALL_DIR};PYTHONDONTWRITEBYTECODE=1"
    FIXTURES_REQUIRED flaplag_install_tree TIMEOUT 60)
endif()
