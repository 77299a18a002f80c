# Flags every library translation unit is built with (issue #2): strict C99, warnings as
# errors, no floating-point contraction (bit-identical ports), no VLAs, per-function stack
# usage files (checked by tests/check_stack.cmake).
function(pn_library_flags target)
  set_target_properties(${target} PROPERTIES C_STANDARD 99 C_STANDARD_REQUIRED ON C_EXTENSIONS OFF)
  target_compile_options(${target} PRIVATE
    -std=c99 -Wall -Wextra -Wpedantic -Wundef -Werror -Wvla -Wshadow -Wstrict-prototypes
    -ffp-contract=off -fno-math-errno -fstack-usage)
endfunction()

# Host tools and tests: warnings on, contraction off (they compare floats with the library).
function(pn_host_flags target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -ffp-contract=off)
endfunction()
