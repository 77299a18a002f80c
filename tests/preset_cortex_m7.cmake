# preset_cortex_m7.cmake - `cmake --preset cortex-m7` + build, as the README shows it, gives
# the core archive needing only memcpy/memset (ctest preset_cortex_m7, issue 19).
#
#   cmake -DSOURCE_DIR=<repo> -DWORK_DIR=<binary dir> -P tests/preset_cortex_m7.cmake
#
# The preset's own binaryDir is build/cortex-m7; -B puts this run in WORK_DIR instead, so a
# developer's build/cortex-m7 is left alone. The symbol check is check_symbols.cmake in
# strict mode, the same as freestanding_arm applies to its hand-compiled archive; then the
# build installs (headers, archive, CMake package, penumbra.pc without -lm).
cmake_minimum_required(VERSION 3.25)
if(NOT SOURCE_DIR OR NOT WORK_DIR)
  message(FATAL_ERROR "preset_cortex_m7: pass -DSOURCE_DIR and -DWORK_DIR")
endif()
find_program(NM arm-none-eabi-nm NO_CACHE)
if(NOT NM)
  message(FATAL_ERROR "preset_cortex_m7: arm-none-eabi-nm not found (make test installs gcc-arm-none-eabi)")
endif()
file(REMOVE_RECURSE "${WORK_DIR}")
foreach(cmd "--preset;cortex-m7;-B;${WORK_DIR}" "--build;${WORK_DIR}")
  execute_process(COMMAND ${CMAKE_COMMAND} ${cmd} WORKING_DIRECTORY ${SOURCE_DIR}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "preset_cortex_m7: cmake ${cmd} failed (${rc}):\n${out}")
  endif()
endforeach()
foreach(d tools tests fuzz ports/opencl)
  if(EXISTS "${WORK_DIR}/${d}")
    message(FATAL_ERROR "preset_cortex_m7: the core-only preset configured ${d}/")
  endif()
endforeach()
execute_process(COMMAND ${CMAKE_COMMAND} -DARCHIVE=${WORK_DIR}/libpenumbra.a -DNM=${NM} -DMODE=strict
                        -DALLOWED=memcpy,memset -P ${CMAKE_CURRENT_LIST_DIR}/check_symbols.cmake
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "preset_cortex_m7: the preset's libpenumbra.a needs more than memcpy/memset (above)")
endif()
# The cross build installs like the host one, without the host-only libm.
execute_process(COMMAND ${CMAKE_COMMAND} --install ${WORK_DIR} --prefix ${WORK_DIR}/prefix
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "preset_cortex_m7: cmake --install failed (${rc}):\n${out}")
endif()
file(GLOB_RECURSE pc "${WORK_DIR}/prefix/*/penumbra.pc")
file(GLOB_RECURSE cfg "${WORK_DIR}/prefix/*/penumbraConfig.cmake")
file(GLOB_RECURSE lib "${WORK_DIR}/prefix/*/libpenumbra.a")
if(NOT pc OR NOT cfg OR NOT lib OR NOT EXISTS "${WORK_DIR}/prefix/include/penumbra/penumbra.h")
  message(FATAL_ERROR "preset_cortex_m7: the install is incomplete:\n${out}")
endif()
file(READ "${pc}" pc_text)
if(pc_text MATCHES "-lm")
  message(FATAL_ERROR "preset_cortex_m7: ${pc} links libm on bare metal:\n${pc_text}")
endif()
message(STATUS "preset_cortex_m7: PASS")
