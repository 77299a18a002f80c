# PnInstall.cmake - what `cmake --install` puts where (issue 19), GNUInstallDirs layout:
#
#   <includedir>/penumbra/*.h                  the public headers
#   <libdir>/libpenumbra.a                     the core (+ libpenumbra_opencl.a where built)
#   <libdir>/cmake/penumbra/                   find_package(penumbra CONFIG): targets
#                                              penumbra::penumbra and penumbra::opencl,
#                                              penumbraConfigVersion.cmake
#   <libdir>/pkgconfig/penumbra.pc             pkg-config (+ penumbra-opencl.pc)
#
# The .pc files compute their prefix from their own location (${pcfiledir}), so a tree
# installed with `cmake --install build --prefix /somewhere` can be moved and still works;
# so does the CMake package (configure_package_config_file's PACKAGE_PREFIX_DIR).

include(CMakePackageConfigHelpers)

set(PN_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/penumbra)
set(PN_PKGCONFIG_DIR ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/penumbra
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT penumbra_dev
        FILES_MATCHING PATTERN "*.h")

install(TARGETS penumbra EXPORT penumbraTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT penumbra_dev)
install(EXPORT penumbraTargets NAMESPACE penumbra:: DESTINATION ${PN_CMAKE_DIR}
        FILE penumbraTargets.cmake COMPONENT penumbra_dev)
# The OpenCL port in an export set of its own, so that a consumer without OpenCL can still
# use the core: penumbraConfig.cmake loads it only where find_package(OpenCL) succeeds.
set(PN_INSTALL_OPENCL 0)
if(TARGET penumbra_opencl)
  set(PN_INSTALL_OPENCL 1)
  install(TARGETS penumbra_opencl EXPORT penumbraOpenCLTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT penumbra_dev)
  install(EXPORT penumbraOpenCLTargets NAMESPACE penumbra:: DESTINATION ${PN_CMAKE_DIR}
          FILE penumbraOpenCLTargets.cmake COMPONENT penumbra_dev)
endif()

configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/penumbraConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/penumbraConfig.cmake
                              INSTALL_DESTINATION ${PN_CMAKE_DIR})
# A static library built for one ABI: the version file also checks the consumer's pointer
# size (a 32-bit Cortex-M archive is not picked up by a 64-bit host project).
write_basic_package_version_file(${PROJECT_BINARY_DIR}/penumbraConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/penumbraConfig.cmake ${PROJECT_BINARY_DIR}/penumbraConfigVersion.cmake
        DESTINATION ${PN_CMAKE_DIR} COMPONENT penumbra_dev)

# pkg-config. Static archives only, so what the final link needs goes in Libs (there is
# no shared library whose own dependencies could hide in Libs.private).
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}" OR IS_ABSOLUTE "${CMAKE_INSTALL_INCLUDEDIR}")
  message(FATAL_ERROR "PnInstall: CMAKE_INSTALL_LIBDIR and CMAKE_INSTALL_INCLUDEDIR must be relative "
                      "to the prefix (the .pc files and the CMake package are relocatable)")
endif()
file(RELATIVE_PATH PN_PC_PREFIX_REL /${PN_PKGCONFIG_DIR} /)
string(REGEX REPLACE "/$" "" PN_PC_PREFIX_REL "${PN_PC_PREFIX_REL}")
# The algorithms left out (PN_ALGORITHMS), as the exported target carries them.
set(PN_PC_CFLAGS_EXTRA "")
foreach(def IN LISTS PN_ALGORITHM_DEFINES)
  string(APPEND PN_PC_CFLAGS_EXTRA " -D${def}")
endforeach()
set(PN_PC_LIBS_EXTRA "")
if(NOT CMAKE_SYSTEM_NAME STREQUAL "Generic")
  set(PN_PC_LIBS_EXTRA " -lm")
endif()
configure_file(${CMAKE_CURRENT_LIST_DIR}/penumbra.pc.in ${PROJECT_BINARY_DIR}/penumbra.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/penumbra.pc DESTINATION ${PN_PKGCONFIG_DIR} COMPONENT penumbra_dev)
if(PN_INSTALL_OPENCL)
  configure_file(${CMAKE_CURRENT_LIST_DIR}/penumbra-opencl.pc.in ${PROJECT_BINARY_DIR}/penumbra-opencl.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/penumbra-opencl.pc DESTINATION ${PN_PKGCONFIG_DIR} COMPONENT penumbra_dev)
endif()
