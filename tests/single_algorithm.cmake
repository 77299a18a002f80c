# single_algorithm.cmake - the library built with one algorithm alone (-DPN_ALGORITHMS=ALGO)
# passes that algorithm's golden frames (the full build's bytes: the same golden file), the
# cross-port test (scalar and OpenCL ports, the same bytes) and the trust-model tests
# (arena bounds, hostile input, the fuzz corpus) on it (issue 47).
#
#   cmake -DSOURCE_DIR=<repo> -DWORK_DIR=<binary dir> -DALGO=<name> -DBUILD_TYPE=<type>
#         -DSCENES=<shared scenes> -DGENERATOR=<generator> -P tests/single_algorithm.cmake
#
# A reduced configure + build of the library, the tools and these five tests, then ctest
# on them in the reduced tree: 25-60 seconds of two cores each.
cmake_minimum_required(VERSION 3.25)
foreach(v SOURCE_DIR WORK_DIR ALGO SCENES GENERATOR)
  if(NOT ${v})
    message(FATAL_ERROR "single_algorithm: pass -D${v}")
  endif()
endforeach()
set(tests test_golden test_crossport test_validation test_arena fuzz_scene_corpus)
set(targets test_golden test_crossport test_validation test_arena fuzz_scene_replay penumbra_cli)
file(REMOVE_RECURSE "${WORK_DIR}")
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR} -G ${GENERATOR}
                        -DCMAKE_BUILD_TYPE=${BUILD_TYPE} -DPN_ALGORITHMS=${ALGO} -DPN_SHARED_SCENES=${SCENES}
                        -DPN_INSTALL=OFF
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "single_algorithm ${ALGO}: configure failed (${rc}):\n${out}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR} -j2 --target ${targets}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "single_algorithm ${ALGO}: build failed (${rc}):\n${out}")
endif()
if(NOT EXISTS "${WORK_DIR}/tests/test_crossport")
  list(REMOVE_ITEM tests test_crossport) # no OpenCL here: the host build's own test says so
endif()
list(JOIN tests "|" pattern)
execute_process(COMMAND ${CMAKE_CTEST_COMMAND} -R "^(${pattern})$" --output-on-failure
                WORKING_DIRECTORY ${WORK_DIR}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "single_algorithm ${ALGO}: tests failed in the reduced build")
endif()
# What the build holds is exactly the one algorithm (the CLI's info line).
execute_process(COMMAND ${WORK_DIR}/tools/penumbra info --no-build OUTPUT_VARIABLE info RESULT_VARIABLE rc)
string(REGEX MATCH "algorithms:[^\n]*" line "${info}")
if(NOT rc EQUAL 0 OR NOT line STREQUAL "algorithms: ${ALGO}")
  message(FATAL_ERROR "single_algorithm ${ALGO}: penumbra info says '${line}'")
endif()
message("single_algorithm: PASS ${ALGO}")
