# Warnings on, as errors in CI-relevant targets; never -ffast-math (the Floquet exponents
# depend on det/log of nearly cancelling products).
function(flaplag_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion)
endfunction()
