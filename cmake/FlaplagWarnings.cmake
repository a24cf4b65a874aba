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

# The front ends (the CLI and the Python module) and the documents layer they share parse options,
# read and write result files; the generator drives GiNaC.  None of the numerics is theirs, so an
# optimized build compiles them at -O1: a third less compile time (a unit of the CLI library:
# 11-13 s of CPU against 19-20 s at -O3) and no measurable cost at run time (a 1501-point sweep
# written as JSON, plotted and reported: 0.55-0.63 s of CPU, 0.54-0.58 s at -O3).  The numbers
# are the same bits at every level (no -ffast-math, no FMA).  The analysis layer is not among
# them: at -O1 its forced response took 11-15 % longer and its set-up up to 16 %.
function(flaplag_front_end_optimization target)
  if(CMAKE_BUILD_TYPE MATCHES "^(Release|RelWithDebInfo|MinSizeRel)$")
    target_compile_options(${target} PRIVATE -O1)
  endif()
endfunction()
