# Warnings on for every target of the project (FLAPLAG_WERROR=ON, as in CI, makes them errors);
# never -ffast-math (the Floquet exponents depend on det/log of nearly cancelling products).
option(FLAPLAG_WERROR "Treat compiler warnings as errors (CI)" OFF)

function(flaplag_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion)
  if(FLAPLAG_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
