#!/bin/sh
# Installs the Debian 12 packages the build and tests need, if any are missing.
# As root: apt-get installs them. Otherwise: prints the exact command and fails.
#   tools/install-deps.sh         what `make demo` and `make test` need
#   tools/install-deps.sh bench   also the benchmark's own: the Embree 3 baseline, gnuplot
#                                 for the plots and valgrind for its profile (make bench)
#   tools/install-deps.sh fuzz    also clang and its libFuzzer/sanitizer runtime (make fuzz)
set -eu
# OpenCL port: headers, the ICD loader to link against, and PoCL as the CPU device.
# Cortex-M7: the cross compiler and newlib's headers (ctest freestanding_arm, the cortex-m7
# preset) and QEMU's mps2-an500 board that runs the firmware example (firmware_same_bytes).
# pkg-config: ctest consumer_pkg_config builds against the installed penumbra.pc.
PKGS="cmake make gcc g++ libtinygltf-dev libstb-dev gcc-arm-none-eabi libnewlib-arm-none-eabi
      qemu-system-arm pkg-config pocl-opencl-icd ocl-icd-opencl-dev opencl-headers"
case "${1:-}" in
  "") ;;
  bench) PKGS="$PKGS libembree-dev gnuplot-nox valgrind" ;;
  fuzz) PKGS="$PKGS clang libclang-rt-14-dev" ;;
  *) echo "usage: $0 [bench|fuzz]" >&2; exit 2 ;;
esac
missing=""
for p in $PKGS; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
[ -z "$missing" ] && exit 0
if [ "$(id -u)" -ne 0 ]; then
  echo "penumbra: missing Debian packages:$missing" >&2
  echo "run:  sudo apt-get update && sudo apt-get install -y$missing" >&2
  exit 1
fi
echo "penumbra: installing$missing" >&2
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends $missing >/dev/null
