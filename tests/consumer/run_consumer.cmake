# run_consumer.cmake - penumbra from another project's point of view (ctest consumer_*).
#
#   cmake -DMODE=<mode> -DWORK_DIR=<dir> -DPREFIX=<install prefix> -DCC=<c compiler>
#         [-DBUILD_DIR=<penumbra build>] [-DSOURCE_DIR=<repo>] [-DLIBDIR=lib]
#         [-DPKG_CONFIG=pkg-config] -P tests/consumer/run_consumer.cmake
#
# MODE=install       cmake --install BUILD_DIR --prefix PREFIX (fresh), and the files are where
#                    GNUInstallDirs says: headers, libpenumbra.a, the CMake package, penumbra.pc
# MODE=find_package  tests/consumer configured with CMAKE_PREFIX_PATH=PREFIX only
#                    (find_package(penumbra CONFIG)), built, run; consumer_opencl too when the
#                    tree has penumbra::opencl
# MODE=pkg_config    consumer.c compiled with CC and `pkg-config --cflags --libs penumbra` of
#                    PREFIX alone, run
# MODE=fetchcontent  tests/consumer with FetchContent of SOURCE_DIR, built, run; penumbra's
#                    tools and tests must not have been configured (not top level)

cmake_minimum_required(VERSION 3.25)
foreach(v MODE WORK_DIR CC)
  if(NOT ${v})
    message(FATAL_ERROR "run_consumer: pass -D${v}=...")
  endif()
endforeach()
if(NOT LIBDIR)
  set(LIBDIR lib)
endif()
set(here "${CMAKE_CURRENT_LIST_DIR}")

function(step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "run_consumer ${MODE}: ${what} failed (${rc}):\n${out}")
  endif()
  message(STATUS "${what}: ok")
  set(step_out "${out}" PARENT_SCOPE)
endfunction()

function(run_program exe)
  step("run ${exe}" ${exe})
  message(STATUS "${step_out}")
endfunction()

if(MODE STREQUAL "install")
  file(REMOVE_RECURSE "${PREFIX}")
  step("cmake --install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX})
  foreach(f include/penumbra/penumbra.h include/penumbra/config.h include/penumbra/check_config.h
            ${LIBDIR}/libpenumbra.a ${LIBDIR}/cmake/penumbra/penumbraConfig.cmake
            ${LIBDIR}/cmake/penumbra/penumbraConfigVersion.cmake
            ${LIBDIR}/cmake/penumbra/penumbraTargets.cmake ${LIBDIR}/pkgconfig/penumbra.pc)
    if(NOT EXISTS "${PREFIX}/${f}")
      message(FATAL_ERROR "run_consumer install: ${PREFIX}/${f} was not installed")
    endif()
  endforeach()
  message(STATUS "run_consumer: PASS install")
elseif(MODE STREQUAL "find_package")
  file(REMOVE_RECURSE "${WORK_DIR}")
  # CMAKE_FIND_USE_PACKAGE_REGISTRY off: only the tree just installed may be found.
  step("configure" ${CMAKE_COMMAND} -S ${here} -B ${WORK_DIR} -DCMAKE_C_COMPILER=${CC}
       -DCMAKE_PREFIX_PATH=${PREFIX} -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
  step("build" ${CMAKE_COMMAND} --build ${WORK_DIR})
  run_program(${WORK_DIR}/consumer)
  if(EXISTS ${PREFIX}/${LIBDIR}/cmake/penumbra/penumbraOpenCLTargets.cmake)
    if(NOT EXISTS ${WORK_DIR}/consumer_opencl)
      message(FATAL_ERROR "run_consumer find_package: the tree has the OpenCL port but penumbra::opencl was not found")
    endif()
    run_program(${WORK_DIR}/consumer_opencl)
  endif()
  message(STATUS "run_consumer: PASS find_package")
elseif(MODE STREQUAL "pkg_config")
  if(NOT PKG_CONFIG)
    find_program(PKG_CONFIG pkg-config NO_CACHE)
  endif()
  if(NOT PKG_CONFIG)
    message(FATAL_ERROR "run_consumer pkg_config: pkg-config not found (Debian: pkg-config, tools/install-deps.sh)")
  endif()
  file(REMOVE_RECURSE "${WORK_DIR}")
  file(MAKE_DIRECTORY "${WORK_DIR}")
  # PKG_CONFIG_LIBDIR replaces the default search path: only the installed tree is seen.
  step("pkg-config" ${CMAKE_COMMAND} -E env PKG_CONFIG_LIBDIR=${PREFIX}/${LIBDIR}/pkgconfig
       ${PKG_CONFIG} --cflags --libs penumbra)
  string(STRIP "${step_out}" flags)
  message(STATUS "pkg-config --cflags --libs penumbra: ${flags}")
  separate_arguments(flags UNIX_COMMAND "${flags}")
  step("compile" ${CC} -std=c99 -Wall -Wextra -Werror ${here}/consumer.c ${flags} -o ${WORK_DIR}/consumer)
  run_program(${WORK_DIR}/consumer)
  message(STATUS "run_consumer: PASS pkg_config")
elseif(MODE STREQUAL "fetchcontent")
  file(REMOVE_RECURSE "${WORK_DIR}")
  step("configure" ${CMAKE_COMMAND} -S ${here} -B ${WORK_DIR} -DCMAKE_C_COMPILER=${CC}
       -DPN_CONSUME=fetchcontent -DPENUMBRA_SOURCE_DIR=${SOURCE_DIR})
  foreach(d tools tests fuzz)
    if(EXISTS ${WORK_DIR}/_deps/penumbra-build/${d})
      message(FATAL_ERROR "run_consumer fetchcontent: penumbra configured its ${d}/ as a subproject")
    endif()
  endforeach()
  step("build" ${CMAKE_COMMAND} --build ${WORK_DIR} --target consumer)
  run_program(${WORK_DIR}/consumer)
  message(STATUS "run_consumer: PASS fetchcontent")
else()
  message(FATAL_ERROR "run_consumer: unknown MODE '${MODE}'")
endif()
