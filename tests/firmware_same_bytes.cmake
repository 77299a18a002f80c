# firmware_same_bytes.cmake - the same bytes on the target (ctest firmware_same_bytes,
# issue 19; DESIGN.md "How the work is checked").
#
#   cmake -DSOURCE_DIR=<repo> -DWORK_DIR=<dir> -DHOST_CC=<cc> [-DQEMU=<qemu-system-arm>]
#         [-DSCENE_C=<spot as C, from tools/pn_mesh_to_c>] -P tests/firmware_same_bytes.cmake
#
# Builds examples/firmware twice from the source tree (penumbra pulled in by
# add_subdirectory, both with examples/firmware/config/fw_config.h): as a host program with
# HOST_CC and as a Cortex-M7 ELF with cmake/arm-none-eabi.cmake. Runs the first directly and
# the second under QEMU's mps2-an500 with semihosting, then requires the same "frame ..."
# lines from both: the FNV-1a checksums of the visibility, RGBA and G-buffer bytes of every
# frame. The small scene's: every algorithm pn_build_info reports, k = 4 and 8, an area and
# a point light, 32 x 32. With SCENE_C (tests/CMakeLists.txt generates it at build time
# from spot.glb; PN_FW_SCENE_C of the example) also spot's ("frame spot ..."): 160 x 120,
# k = 8, its area light, the reference and Monte Carlo shadow maps. The line counts are
# checked too (4 per algorithm, 2 for spot), so a target that stops early cannot pass by
# printing less; and the target's painted stack must not have been used to its last word.
# The arena and stack lines differ between the two (8-byte pointers on the host; the host
# does not measure its stack) and are only shown.

cmake_minimum_required(VERSION 3.25)

if(NOT SOURCE_DIR OR NOT WORK_DIR OR NOT HOST_CC)
  message(FATAL_ERROR "firmware_same_bytes: pass -DSOURCE_DIR, -DWORK_DIR and -DHOST_CC")
endif()
set(install_hint "make test installs them (tools/install-deps.sh); by hand: sudo apt-get install -y \
gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm")
find_program(ARM_GCC arm-none-eabi-gcc NO_CACHE)
if(NOT QEMU OR NOT EXISTS "${QEMU}")
  find_program(QEMU qemu-system-arm NO_CACHE)
endif()
if(NOT ARM_GCC OR NOT QEMU)
  message(FATAL_ERROR "firmware_same_bytes: arm-none-eabi-gcc or qemu-system-arm not found: ${install_hint}")
endif()

set(example "${SOURCE_DIR}/examples/firmware")
set(scene_args "")
if(SCENE_C)
  if(NOT EXISTS "${SCENE_C}")
    message(FATAL_ERROR "firmware_same_bytes: SCENE_C ${SCENE_C} does not exist (build the firmware_spot_c target)")
  endif()
  set(scene_args "-DPN_FW_SCENE_C=${SCENE_C}")
endif()
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

function(fw_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "firmware_same_bytes: ${what} failed (${rc}):\n${out}")
  endif()
endfunction()

# Both builds at -O2 like the library's default (RelWithDebInfo); -ffp-contract=off comes
# with the library's flags on both, the target flags from the toolchain file.
fw_step("host configure" ${CMAKE_COMMAND} -S ${example} -B ${WORK_DIR}/host
        -DCMAKE_C_COMPILER=${HOST_CC} -DCMAKE_BUILD_TYPE=RelWithDebInfo ${scene_args})
fw_step("host build" ${CMAKE_COMMAND} --build ${WORK_DIR}/host)
fw_step("Cortex-M7 configure" ${CMAKE_COMMAND} -S ${example} -B ${WORK_DIR}/m7
        -DCMAKE_TOOLCHAIN_FILE=${SOURCE_DIR}/cmake/arm-none-eabi.cmake -DCMAKE_BUILD_TYPE=RelWithDebInfo
        ${scene_args})
fw_step("Cortex-M7 build" ${CMAKE_COMMAND} --build ${WORK_DIR}/m7)

execute_process(COMMAND ${WORK_DIR}/host/fw_host RESULT_VARIABLE host_rc
                OUTPUT_VARIABLE host_out ERROR_VARIABLE host_err TIMEOUT 60)
if(NOT host_rc EQUAL 0)
  message(FATAL_ERROR "firmware_same_bytes: the host example failed (${host_rc}):\n${host_out}${host_err}")
endif()

# QEMU 7.2 writes semihosting output (SYS_WRITE0) to its stderr; SYS_EXIT with
# ADP_Stopped_ApplicationExit ends it with status 0, anything else with 1. The timeout
# catches a target that hangs (a fault loop, a missing FPU enable before the handler).
# Wall-clock milliseconds since the epoch (CMake's math is integer-only: seconds and
# microseconds separately).
function(now_ms out_var)
  string(TIMESTAMP t "%s %f")
  string(REGEX REPLACE "^([0-9]+) 0*([0-9]+)$" "\\1;\\2" t "${t}")
  list(GET t 0 s)
  list(GET t 1 us)
  math(EXPR ms "${s} * 1000 + ${us} / 1000")
  set(${out_var} ${ms} PARENT_SCOPE)
endfunction()
now_ms(t0)
execute_process(COMMAND ${QEMU} -M mps2-an500 -nographic -monitor none -serial null -semihosting
                        -kernel ${WORK_DIR}/m7/fw.elf
                RESULT_VARIABLE m7_rc OUTPUT_VARIABLE m7_out ERROR_VARIABLE m7_out TIMEOUT 120)
now_ms(t1)
math(EXPR ms "${t1} - ${t0}")
file(WRITE ${WORK_DIR}/host.txt "${host_out}")
file(WRITE ${WORK_DIR}/m7.txt "${m7_out}")
if(NOT m7_rc EQUAL 0)
  message(FATAL_ERROR "firmware_same_bytes: the Cortex-M7 run failed (${m7_rc}):\n${m7_out}")
endif()

function(frame_lines text out_var)
  string(REPLACE "\r" "" text "${text}")
  string(REPLACE "\n" ";" lines "${text}")
  set(frames "")
  foreach(l IN LISTS lines)
    if(l MATCHES "^frame ")
      list(APPEND frames "${l}")
    endif()
  endforeach()
  set(${out_var} "${frames}" PARENT_SCOPE)
endfunction()
frame_lines("${host_out}" host_frames)
frame_lines("${m7_out}" m7_frames)
list(LENGTH host_frames nhost)
list(LENGTH m7_frames nm7)
set(host_spot "${host_frames}")
list(FILTER host_spot INCLUDE REGEX "^frame spot ")
list(LENGTH host_spot nspot)
math(EXPR nsmall "${nhost} - ${nspot}")

message(STATUS "host:\n${host_out}")
message(STATUS "Cortex-M7 (QEMU mps2-an500, ${ms} ms wall):\n${m7_out}")

# The small scene: each compiled-in algorithm x k in {4, 8} x {area, point}; the example
# prints no frame line for an algorithm pn_build_info does not list, and fails on any
# render error. spot: the reference and Monte Carlo shadow maps (every algorithm is
# compiled into the example).
if(nsmall LESS 4 OR NOT nhost EQUAL nm7)
  message(FATAL_ERROR "firmware_same_bytes: ${nhost} frame lines on the host, ${nm7} on the target")
endif()
math(EXPR rem "${nsmall} % 4")
if(NOT rem EQUAL 0)
  message(FATAL_ERROR "firmware_same_bytes: ${nsmall} small-scene frame lines is not 4 per algorithm")
endif()
if(SCENE_C AND NOT nspot EQUAL 2)
  message(FATAL_ERROR "firmware_same_bytes: ${nspot} spot frame lines on the host, 2 expected")
elseif(NOT SCENE_C AND NOT nspot EQUAL 0)
  message(FATAL_ERROR "firmware_same_bytes: spot frame lines without SCENE_C")
endif()
# The stack: m7/startup.c paints all of it at reset; used to its last word means it may
# have overflowed into .bss.
if(NOT m7_out MATCHES "stack high water ([0-9]+) of ([0-9]+) bytes")
  message(FATAL_ERROR "firmware_same_bytes: the target printed no stack high-water line")
endif()
set(stack_used ${CMAKE_MATCH_1})
set(stack_size ${CMAKE_MATCH_2})
if(NOT stack_used LESS stack_size)
  message(FATAL_ERROR "firmware_same_bytes: the target used all ${stack_size} bytes of its stack")
endif()
set(diff "")
foreach(i RANGE 0 ${nhost})
  if(i EQUAL nhost)
    break()
  endif()
  list(GET host_frames ${i} h)
  list(GET m7_frames ${i} m)
  if(NOT h STREQUAL m)
    string(APPEND diff "  host:   ${h}\n  target: ${m}\n")
  endif()
endforeach()
if(diff)
  message(FATAL_ERROR "firmware_same_bytes: the Cortex-M7 bytes differ from the host's:\n${diff}")
endif()
if(SCENE_C)
  set(what "${nsmall} small-scene, ${nspot} spot 160x120")
else()
  set(what "${nsmall} small-scene; spot not built: no SCENE_C")
endif()
message(STATUS "firmware_same_bytes: PASS ${nhost} frames identical on host and Cortex-M7 (${what}; \
QEMU run ${ms} ms; stack ${stack_used} of ${stack_size} bytes)")
