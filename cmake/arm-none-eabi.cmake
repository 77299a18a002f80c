# arm-none-eabi.cmake - CMake toolchain file for bare-metal Cortex-M7 (issue 19).
#
#   cmake --preset cortex-m7                     (CMakePresets.json), or
#   cmake -S . -B build-m7 -DCMAKE_TOOLCHAIN_FILE=cmake/arm-none-eabi.cmake \
#         -DPN_BUILD_TOOLS=OFF -DPN_BUILD_TESTS=OFF
#
# The target flags are the ones ctest freestanding_arm proves (tests/build_freestanding.cmake):
# Cortex-M7 with the double-precision FPU (fpv5-d16), hard-float ABI, Thumb-2, freestanding,
# no errno from math (__builtin_sqrtf stays one vsqrt.f32) and no floating-point
# contraction (the ports and the host are bit-identical only without FMA contraction).
# Debian 12: apt-get install gcc-arm-none-eabi libnewlib-arm-none-eabi (tools/install-deps.sh).
# Another Cortex-M: set PN_ARM_CPU_FLAGS before (or on the command line), e.g.
#   -DPN_ARM_CPU_FLAGS="-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard"
# (a single-precision FPU is enough: the core uses no double).

set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)

set(PN_ARM_PREFIX arm-none-eabi- CACHE STRING "Cross tool prefix (arm-none-eabi-gcc, -ar, -nm, ...)")
find_program(PN_ARM_GCC_PATH ${PN_ARM_PREFIX}gcc REQUIRED)
get_filename_component(pn_arm_bin "${PN_ARM_GCC_PATH}" DIRECTORY)
set(CMAKE_C_COMPILER "${PN_ARM_GCC_PATH}")
set(CMAKE_CXX_COMPILER "${pn_arm_bin}/${PN_ARM_PREFIX}g++")
set(CMAKE_ASM_COMPILER "${PN_ARM_GCC_PATH}")
set(CMAKE_AR "${pn_arm_bin}/${PN_ARM_PREFIX}ar" CACHE FILEPATH "")
set(CMAKE_RANLIB "${pn_arm_bin}/${PN_ARM_PREFIX}ranlib" CACHE FILEPATH "")
set(CMAKE_NM "${pn_arm_bin}/${PN_ARM_PREFIX}nm" CACHE FILEPATH "")
set(CMAKE_OBJCOPY "${pn_arm_bin}/${PN_ARM_PREFIX}objcopy" CACHE FILEPATH "")
set(CMAKE_SIZE "${pn_arm_bin}/${PN_ARM_PREFIX}size" CACHE FILEPATH "")

set(PN_ARM_CPU_FLAGS "-mcpu=cortex-m7 -mthumb -mfpu=fpv5-d16 -mfloat-abi=hard"
    CACHE STRING "Target CPU and float ABI flags")
set(CMAKE_C_FLAGS_INIT "${PN_ARM_CPU_FLAGS} -ffreestanding -fno-math-errno -ffp-contract=off")
set(CMAKE_CXX_FLAGS_INIT "${PN_ARM_CPU_FLAGS} -ffreestanding -fno-math-errno -ffp-contract=off")
set(CMAKE_ASM_FLAGS_INIT "${PN_ARM_CPU_FLAGS}")

# No C runtime to link a test program against: compiler checks build a static library.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

# Programs from the host; libraries, headers and packages only from the target's sysroot.
# Debian puts newlib under /usr/lib/arm-none-eabi; Arm's own toolchains beside bin/.
foreach(pn_root /usr/lib/arm-none-eabi "${pn_arm_bin}/../arm-none-eabi")
  if(IS_DIRECTORY "${pn_root}/include")
    set(CMAKE_FIND_ROOT_PATH "${pn_root}")
    break()
  endif()
endforeach()
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
