# golden_target_arch.cmake - the golden frames (tests/golden/frames.txt: every built-in and
# shared scene, every exact algorithm) rendered by a library compiled for this machine's
# CPU (-DPN_TARGET_ARCH=native, as make bench builds it): the same bytes as the default
# target's. A separate Release configuration in WORK_DIR; only test_golden is built.
#
#   cmake -DSOURCE_DIR=<repo> -DWORK_DIR=<binary dir> [-DARCH=native] -P tests/golden_target_arch.cmake
cmake_minimum_required(VERSION 3.25)
if(NOT SOURCE_DIR OR NOT WORK_DIR)
  message(FATAL_ERROR "golden_target_arch: pass -DSOURCE_DIR and -DWORK_DIR")
endif()
if(NOT ARCH)
  set(ARCH native)
endif()
file(REMOVE_RECURSE "${WORK_DIR}")
foreach(cmd "-S;${SOURCE_DIR};-B;${WORK_DIR};-DCMAKE_BUILD_TYPE=Release;-DPN_TARGET_ARCH=${ARCH};-DPN_OPENCL=OFF;-DPN_INSTALL=OFF"
            "--build;${WORK_DIR};--target;test_golden")
  execute_process(COMMAND ${CMAKE_COMMAND} ${cmd} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "golden_target_arch: cmake ${cmd} failed (${rc}):\n${out}")
  endif()
endforeach()
execute_process(COMMAND ${WORK_DIR}/tests/test_golden RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "golden_target_arch: test_golden with -march=${ARCH} failed (${rc})")
endif()
message("golden_target_arch: PASS (-march=${ARCH})")
