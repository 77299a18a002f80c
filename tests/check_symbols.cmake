# check_symbols.cmake - what a static archive of the library needs from the outside world.
#
#   cmake -DARCHIVE=libpenumbra.a [-DNM=nm] [-DMODE=heap|strict]
#         [-DALLOWED=memcpy,memset] -P tests/check_symbols.cmake
#
# Runs `nm -A -P` on ARCHIVE and collects its undefined symbols: every symbol some member
# references (nm types U, w, v) that no member of the archive defines globally. A
# reference from one member to a function of another member (pn_scene.c.o -> pn_fail) is
# therefore not "undefined": only what the final link would have to find elsewhere is.
#
# MODE=heap (default; DESIGN.md invariant 1, "one arena, no malloc"): fails if any
#   undefined symbol allocates: the C heap (malloc, calloc, realloc, reallocarray, free,
#   aligned_alloc, posix_memalign, memalign, valloc, pvalloc), functions that return heap
#   memory (strdup, strndup), alloca when it is not a compiler builtin, and the C++
#   operators new/delete (_Znw*, _Zna*, _Zdl*, _Zda*). A __builtin_alloca or a VLA leaves
#   no symbol; those are caught by -Wvla and by the call-graph test (no_recursion_bounded_stack).
# MODE=strict (the freestanding Cortex-M7 archive): additionally fails on ANY undefined
#   symbol not listed in ALLOWED (comma-separated, default "memcpy,memset"). memcpy and
#   memset are the two functions GCC may call even in -ffreestanding code (struct copies,
#   zeroing) and the ones every bare-metal C runtime provides. No compiler-runtime helper
#   is allowed today, because none is needed: with -mfpu=fpv5-d16 -mfloat-abi=hard the FPU
#   does float and double arithmetic in hardware (no __aeabi_d*/__aeabi_f* soft-float
#   calls), __builtin_sqrtf with -fno-math-errno is one vsqrt.f32, and GCC turns the
#   only 64-bit divisions (by the constant 10 in pn_context.c) into multiplications. If a
#   change needs a libgcc helper (e.g. __aeabi_uldivmod for a 64-bit division by a
#   variable), add it to ALLOWED in tests/CMakeLists.txt with a comment saying which code
#   needs it and why it cannot be avoided.
#
# Every offending symbol is printed with the archive members that reference it.

cmake_minimum_required(VERSION 3.25)

if(NOT ARCHIVE)
  message(FATAL_ERROR "check_symbols: pass -DARCHIVE=<static library>")
endif()
if(NOT EXISTS "${ARCHIVE}")
  message(FATAL_ERROR "check_symbols: archive '${ARCHIVE}' does not exist (was the library built?)")
endif()
if(NOT MODE)
  set(MODE heap)
endif()
if(NOT MODE STREQUAL "heap" AND NOT MODE STREQUAL "strict")
  message(FATAL_ERROR "check_symbols: MODE must be heap or strict, not '${MODE}'")
endif()
if(NOT DEFINED ALLOWED)
  set(ALLOWED "memcpy,memset")
endif()
string(REPLACE "," ";" allowed "${ALLOWED}")
if(NOT NM)
  set(NM nm)
endif()
if(NOT IS_ABSOLUTE "${NM}")
  find_program(nm_path NAMES "${NM}")
  if(NOT nm_path)
    message(FATAL_ERROR "check_symbols: '${NM}' not found in PATH")
  endif()
  set(NM "${nm_path}")
endif()

set(heap_symbols malloc calloc realloc reallocarray free aligned_alloc posix_memalign memalign
                 valloc pvalloc strdup strndup alloca)

execute_process(COMMAND "${NM}" -A -P "${ARCHIVE}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "check_symbols: '${NM} -A -P ${ARCHIVE}' failed (${rc}):\n${err}")
endif()

# POSIX format with -A: "archive[member]: name type [value size]". Brackets would confuse
# CMake's list splitting, so they are rewritten first.
string(REPLACE "[" "<" out "${out}")
string(REPLACE "]" ">" out "${out}")
string(REPLACE ";" "," out "${out}")
string(REPLACE "\n" ";" lines "${out}")

set(defined "")
set(undef_names "")
set(members "")
foreach(line IN LISTS lines)
  if(line STREQUAL "")
    continue()
  endif()
  if(NOT line MATCHES "^.*<([^>]*)>: ([^ ]+) ([A-Za-z?])( |$)")
    continue()
  endif()
  set(member "${CMAKE_MATCH_1}")
  set(sym "${CMAKE_MATCH_2}")
  set(type "${CMAKE_MATCH_3}")
  list(APPEND members "${member}")
  if(type STREQUAL "U" OR type STREQUAL "w" OR type STREQUAL "v")
    list(APPEND undef_names "${sym}")
    # Which members reference the symbol, as a variable per symbol.
    string(MAKE_C_IDENTIFIER "ref_${sym}" var)
    list(APPEND ${var} "${member}")
  elseif(type MATCHES "^[A-Z]$" OR type STREQUAL "u" OR type STREQUAL "i")
    # Global definitions resolve references from other members.
    list(APPEND defined "${sym}")
  endif()
endforeach()
list(REMOVE_DUPLICATES members)
if(NOT members)
  message(FATAL_ERROR "check_symbols: no symbols read from '${ARCHIVE}' (is it an archive nm understands?)\n${err}")
endif()

list(REMOVE_DUPLICATES undef_names)
list(SORT undef_names)
set(external "")
foreach(sym IN LISTS undef_names)
  if(NOT sym IN_LIST defined)
    list(APPEND external "${sym}")
  endif()
endforeach()

set(bad "")
set(bad_report "")
set(report "")
foreach(sym IN LISTS external)
  string(MAKE_C_IDENTIFIER "ref_${sym}" var)
  set(refs ${${var}})
  list(REMOVE_DUPLICATES refs)
  string(REPLACE ";" ", " refs "${refs}")
  set(why "")
  if(sym IN_LIST heap_symbols OR sym MATCHES "^_Z(nw|na|dl|da)")
    set(why "allocates (DESIGN.md invariant 1: one arena, no malloc)")
  elseif(MODE STREQUAL "strict" AND NOT sym IN_LIST allowed)
    set(why "not in the freestanding allow-list (${ALLOWED})")
  endif()
  string(APPEND report "  ${sym}  <- ${refs}\n")
  if(why)
    list(APPEND bad "${sym}")
    string(APPEND bad_report "  ${sym}: ${why}\n    referenced by: ${refs}\n")
  endif()
endforeach()

list(LENGTH members nmembers)
if(bad)
  message(FATAL_ERROR "check_symbols: ${ARCHIVE} (${MODE} mode, ${nmembers} objects) has forbidden "
                      "undefined symbols:\n${bad_report}All undefined symbols:\n${report}")
endif()
if(NOT external)
  set(report "  (none)\n")
endif()
message(STATUS "check_symbols: ${ARCHIVE} (${MODE} mode, ${nmembers} objects): OK. Undefined symbols:\n${report}")
