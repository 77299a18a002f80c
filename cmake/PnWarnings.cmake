# Flags every library translation unit is built with (issue #2): strict C99, warnings as
# errors, no floating-point contraction (bit-identical ports), no VLAs, per-function stack
# usage files; and no trapping math: the library reads no floating-point exception flag, so
# the compiler may evaluate an operation whose result a select may drop (if-conversion),
# which lets it vectorize loops of selects such as MCSM's eight-ray set-up (kernels/
# pn_mcsm.h). It changes no value: no reassociation, contraction or finite-math assumption
# comes with it (the golden frames and the cross-port tests are the same bytes). PN_LIBRARY_C_OPTIONS is also what tests/CMakeLists.txt compiles its probes
# with (no_vla_compiles), so the tests exercise exactly these flags.
set(PN_LIBRARY_C_OPTIONS
    -std=c99 -Wall -Wextra -Wpedantic -Wundef -Werror -Wvla -Wshadow -Wstrict-prototypes
    -ffp-contract=off -fno-math-errno -fno-trapping-math -fstack-usage)

# GCC >= 10 also writes a per-object call graph (<object stem>.ci, VCG format) with each
# function's frame size (su) and its dynamically sized stack objects (da: VLAs, alloca).
# tests/check_callgraph.c reads them (ctest no_recursion_bounded_stack): no recursion, no
# dynamic stack objects, indirect calls only at the documented dispatch sites, and the
# worst-case stack of every public function within budget.
function(pn_library_flags target)
  set_target_properties(${target} PROPERTIES C_STANDARD 99 C_STANDARD_REQUIRED ON C_EXTENSIONS OFF)
  target_compile_options(${target} PRIVATE ${PN_LIBRARY_C_OPTIONS}
    $<$<AND:$<C_COMPILER_ID:GNU>,$<VERSION_GREATER_EQUAL:$<C_COMPILER_VERSION>,10>>:-fcallgraph-info=su,da>)
endfunction()

# Host tools and tests: warnings on, contraction off (they compare floats with the library).
function(pn_host_flags target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -ffp-contract=off
    $<$<COMPILE_LANGUAGE:C>:-Werror=implicit-function-declaration -Werror=int-conversion>)
endfunction()
