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
# Configures (the preset, then `extra`), builds and installs into dir/prefix; the archive
# must need only memcpy/memset (check_symbols.cmake in strict mode, as freestanding_arm
# applies it to its hand-compiled archive).
function(pn_preset_build dir extra)
  file(REMOVE_RECURSE "${dir}")
  foreach(cmd "--preset;cortex-m7;-B;${dir};${extra}" "--build;${dir}" "--install;${dir};--prefix;${dir}/prefix")
    execute_process(COMMAND ${CMAKE_COMMAND} ${cmd} WORKING_DIRECTORY ${SOURCE_DIR}
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "preset_cortex_m7: cmake ${cmd} failed (${rc}):\n${out}")
    endif()
  endforeach()
  execute_process(COMMAND ${CMAKE_COMMAND} -DARCHIVE=${dir}/libpenumbra.a -DNM=${NM} -DMODE=strict
                          -DALLOWED=memcpy,memset -P ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/check_symbols.cmake
                  RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "preset_cortex_m7: ${dir}/libpenumbra.a needs more than memcpy/memset (above)")
  endif()
endfunction()

pn_preset_build("${WORK_DIR}" "")
foreach(d tools tests fuzz ports/opencl)
  if(EXISTS "${WORK_DIR}/${d}")
    message(FATAL_ERROR "preset_cortex_m7: the core-only preset configured ${d}/")
  endif()
endforeach()
# The cross build installs like the host one, without the host-only libm.
file(GLOB_RECURSE pc "${WORK_DIR}/prefix/*/penumbra.pc")
file(GLOB_RECURSE cfg "${WORK_DIR}/prefix/*/penumbraConfig.cmake")
file(GLOB_RECURSE lib "${WORK_DIR}/prefix/*/libpenumbra.a")
if(NOT pc OR NOT cfg OR NOT lib OR NOT EXISTS "${WORK_DIR}/prefix/include/penumbra/penumbra.h")
  message(FATAL_ERROR "preset_cortex_m7: the install in ${WORK_DIR}/prefix is incomplete")
endif()
file(READ "${pc}" pc_text)
if(pc_text MATCHES "-lm")
  message(FATAL_ERROR "preset_cortex_m7: ${pc} links libm on bare metal:\n${pc_text}")
endif()
# A reduced configuration as a product would ship it: one exact and one approximate
# algorithm (PN_ALGORITHMS), the same strict symbol check, and its pkg-config file carries
# the configuration (the algorithms left out) to the consumer.
set(small "${WORK_DIR}-small")
pn_preset_build("${small}" "-DPN_ALGORITHMS=reference\\;mcsm")
file(GLOB_RECURSE pc "${small}/prefix/*/penumbra.pc")
file(READ "${pc}" pc_text)
foreach(def PN_ENABLE_GEARS=0 PN_ENABLE_RAYTRACE=0 PN_ENABLE_SRT=0 PN_ENABLE_OCCTEX=0 PN_ENABLE_WEDGES=0)
  if(NOT pc_text MATCHES "-D${def}")
    message(FATAL_ERROR "preset_cortex_m7: the reduced build's ${pc} does not carry -D${def}:\n${pc_text}")
  endif()
endforeach()
if(pc_text MATCHES "PN_ENABLE_(REFERENCE|MCSM)")
  message(FATAL_ERROR "preset_cortex_m7: the reduced build's ${pc} leaves out an algorithm it has:\n${pc_text}")
endif()
file(SIZE ${WORK_DIR}/libpenumbra.a full_bytes)
file(SIZE ${small}/libpenumbra.a small_bytes)
message(STATUS "preset_cortex_m7: libpenumbra.a ${full_bytes} bytes, reference;mcsm alone ${small_bytes} bytes")
message(STATUS "preset_cortex_m7: PASS")
