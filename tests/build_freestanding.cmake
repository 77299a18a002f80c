# build_freestanding.cmake - the core as bare-metal firmware would build it (ctest
# freestanding_arm; DESIGN.md: include/, src/, kernels/ and ports/scalar/ "build
# freestanding for a bare-metal ARM target").
#
#   cmake -DSOURCE_DIR=<repo> -DOUT_DIR=<dir> [-DCC=<arm-none-eabi-gcc>] -P tests/build_freestanding.cmake
#
# Compiles every src/*.c and ports/scalar/*.c for a Cortex-M7 with a double-precision FPU
# (Debian's gcc-arm-none-eabi, headers from libnewlib-arm-none-eabi), with the library's
# warning flags, -Werror and -ffreestanding; archives them into OUT_DIR/libpenumbra_m7.a;
# then tests/check_symbols.cmake in strict mode: the archive may need memcpy and memset
# from the outside world and nothing else (no libc, no libm, no libgcc helper, no heap).
# The objects also carry -fstack-usage, -fcallgraph-info=su,da and -fdump-ipa-cgraph
# output for ctest no_recursion_bounded_stack_m7 (these flags only write side files; the
# code is the same).

cmake_minimum_required(VERSION 3.25)

set(install_hint "The freestanding check needs Debian's ARM cross compiler, which `make test` installs \
(tools/install-deps.sh). By hand: sudo apt-get install -y gcc-arm-none-eabi libnewlib-arm-none-eabi, \
then re-run ctest (no re-configure needed).")

if(NOT SOURCE_DIR OR NOT OUT_DIR)
  message(FATAL_ERROR "build_freestanding: pass -DSOURCE_DIR=<repository> -DOUT_DIR=<build directory>")
endif()
if(NOT CC OR NOT EXISTS "${CC}")
  # Found at test time, so installing the package after configuring is enough.
  find_program(CC_FOUND arm-none-eabi-gcc)
  if(NOT CC_FOUND)
    message(FATAL_ERROR "build_freestanding: arm-none-eabi-gcc not found.\n${install_hint}")
  endif()
  set(CC "${CC_FOUND}")
endif()
get_filename_component(cc_dir "${CC}" DIRECTORY)
find_program(AR NAMES arm-none-eabi-ar HINTS "${cc_dir}" NO_CACHE)
find_program(NM NAMES arm-none-eabi-nm HINTS "${cc_dir}" NO_CACHE)
if(NOT AR OR NOT NM)
  message(FATAL_ERROR "build_freestanding: arm-none-eabi-ar / arm-none-eabi-nm not found next to ${CC} "
                      "(Debian package binutils-arm-none-eabi, pulled in by gcc-arm-none-eabi).\n${install_hint}")
endif()

set(target_flags -mcpu=cortex-m7 -mthumb -mfpu=fpv5-d16 -mfloat-abi=hard -ffreestanding
                 -fno-math-errno -ffp-contract=off)
set(warn_flags -std=c99 -Wall -Wextra -Wpedantic -Wundef -Werror -Wvla -O2)
set(side_files -fstack-usage -fcallgraph-info=su,da -fdump-ipa-cgraph)
set(includes "-I${SOURCE_DIR}/include" "-I${SOURCE_DIR}/src" "-I${SOURCE_DIR}/kernels"
             "-I${SOURCE_DIR}/ports/scalar")

file(GLOB sources "${SOURCE_DIR}/src/*.c" "${SOURCE_DIR}/ports/scalar/*.c")
list(SORT sources)
if(NOT sources)
  message(FATAL_ERROR "build_freestanding: no sources under ${SOURCE_DIR}/src")
endif()

set(obj_dir "${OUT_DIR}/m7")
file(REMOVE_RECURSE "${obj_dir}")
file(MAKE_DIRECTORY "${obj_dir}")
set(archive "${OUT_DIR}/libpenumbra_m7.a")
file(REMOVE "${archive}")

execute_process(COMMAND "${CC}" --version OUTPUT_VARIABLE version ERROR_QUIET)
string(REGEX REPLACE "\n.*" "" version "${version}")
message(STATUS "build_freestanding: ${version}")
string(REPLACE ";" " " shown "${target_flags} ${warn_flags}")
message(STATUS "build_freestanding: flags ${shown}")

set(objects "")
set(errors "")
foreach(src IN LISTS sources)
  file(RELATIVE_PATH rel "${SOURCE_DIR}" "${src}")
  string(REPLACE "/" "_" obj "${rel}")
  set(obj "${obj_dir}/${obj}.o")
  execute_process(
    COMMAND "${CC}" ${target_flags} ${warn_flags} ${side_files} ${includes} -c "${src}" -o "${obj}"
    WORKING_DIRECTORY "${obj_dir}"
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    string(APPEND errors "--- ${rel} (exit ${rc}):\n${out}\n")
  else()
    if(NOT out STREQUAL "")
      message("${rel}:\n${out}")
    endif()
    list(APPEND objects "${obj}")
  endif()
endforeach()
if(errors)
  message(FATAL_ERROR "build_freestanding: the core does not build freestanding for Cortex-M7:\n${errors}")
endif()

execute_process(COMMAND "${AR}" rcs "${archive}" ${objects}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "build_freestanding: ${AR} failed (${rc}):\n${out}")
endif()
list(LENGTH objects nobj)
message(STATUS "build_freestanding: ${nobj} objects -> ${archive}")

# Strict: see check_symbols.cmake for why exactly these two, and what to do if a libgcc
# helper ever becomes necessary.
execute_process(COMMAND "${CMAKE_COMMAND}" -DARCHIVE=${archive} -DNM=${NM} -DMODE=strict
                        -DALLOWED=memcpy,memset -P "${CMAKE_CURRENT_LIST_DIR}/check_symbols.cmake"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "build_freestanding: libpenumbra_m7.a needs symbols a bare-metal target does not have (above)")
endif()
