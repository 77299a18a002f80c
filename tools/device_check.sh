#!/usr/bin/env bash
# tools/device_check.sh - the OpenCL port on a GPU, proved by one command (docs/opencl.md,
# "Device check"). On a fresh machine with a GPU it
#   1. unpacks the Debian packages carried in .debs/ (dpkg -x into a prefix, never into /),
#   2. registers the NVIDIA driver's OpenCL ICD (libnvidia-opencl.so.1) when the driver ships one,
#   3. lists the OpenCL devices (clinfo -l where there is one, and penumbra info),
#   4. builds the library, the CLI, test_crossport, test_golden and bench_ports (Release),
#   5. runs test_crossport and the golden frames (test_golden --port opencl) on the GPU,
#   6. benchmarks every algorithm on three shared scenes at 1024x1024: the scalar port on
#      every core beside the OpenCL port on the GPU, every frame compared byte for byte,
#   7. writes $OUT/summary.md (devices, each step's result, the benchmark table) and the logs.
# Without a GPU it does the same on PoCL (the CPU) and says "no GPU: PoCL fallback".
#
# Usage (on the machine that runs the check):
#   tools/device_check.sh [--short] [--build-dir DIR] [--out DIR] [--device SPEC]
#                         [--size N] [--k K] [--reps N] [--scenes TEXT,TEXT,...] [--budget SECONDS]
#     --short       tiny run (one scene at 64x48, two algorithms, the built-in golden scene,
#                   no test_crossport): what ctest device_check_short runs on PoCL
#     --build-dir   use this build tree; an existing one is used as it is (no configure, no
#                   build). Default: build-device/ in the repository, configured and built
#     --out         where the summary and logs go (default: $OUT, else ./device-check-out);
#                   at most 8 files, none in a subfolder (what the device tool brings back)
#     --device      the OpenCL device string (penumbra/opencl.h: gpu, gpu:1, cpu, P:D, a name
#                   fragment); default: gpu when there is one, else the port's default (PoCL)
#     --size/--k/--reps/--scenes   the benchmark (default 1024, k 8, 3 repetitions, the
#                   scenes of PN_BENCH_SCENES_DEFAULT below: objects over a ground, a furnished
#                   interior, foliage); --budget: seconds for the whole run
#                   (default 450): a step that would start past it is skipped and says so
# Environment: PN_DEBS (the carried .debs, default .debs/ in the repository), PN_PREFIX (where
# they are unpacked, default $TMPDIR/pn-device-prefix), PN_SCENES (a scene folder, when neither
# ../shared/scenes nor .scenes/ has one), OUT.
#
# Preparation (here, on a machine with apt and Debian mirrors; the device has no network):
#   tools/device_check.sh --fetch-debs [--with-toolchain]   download into .debs/ what the
#                   device lacks (OpenCL loader and headers, clinfo, tinygltf, stb; with
#                   --with-toolchain also cmake, make and ninja into .debs/toolchain/, ~12 MB)
#   tools/device_check.sh --stage-scenes   copy ../shared/scenes into .scenes/ (44 MB: the
#                   device gets only the repository; ../shared does not travel)
#   tools/device_check.sh --prepare        both
# .debs/, .scenes/, build-device/ and device-check-out/ are in .gitignore.
set -u

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
PN_BENCH_SCENES_DEFAULT="chess_set,grey_white_room,copper_beech"

# Debian packages the device lacks (bookworm, amd64). Runtime and headers of the build:
PN_DEBS_RUNTIME="ocl-icd-libopencl1 ocl-icd-opencl-dev opencl-c-headers clinfo libtinygltf-dev libtinygltf2d libstb-dev libstb0"
# Only if the device has no cmake, make or ninja (KINDS.md lists cmake and ninja there):
PN_DEBS_TOOLCHAIN="cmake cmake-data libjsoncpp25 librhash0 libuv1 libarchive13 libcurl4 libnghttp2-14 librtmp1 libssh2-1 libpsl5 libldap-2.5-0 libsasl2-2 libbrotli1 make ninja-build"

die() { echo "device_check: $*" >&2; exit 2; }

# ---- preparation (here) --------------------------------------------------------------------

fetch_debs() {
    local with_toolchain=$1 debs=${PN_DEBS:-$here/.debs} lists=/tmp/pn-amd64-lists
    command -v apt-get >/dev/null || die "--fetch-debs needs apt-get (a Debian machine with its mirrors)"
    local o=(-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 "-oDir::State::Lists=$lists")
    mkdir -p "$debs" "$lists/partial" || die "cannot create $debs"
    echo "device_check: apt-get update (amd64 lists in $lists)"
    apt-get "${o[@]}" update >/dev/null || die "apt-get update failed"
    # shellcheck disable=SC2086
    (cd "$debs" && apt-get "${o[@]}" download $PN_DEBS_RUNTIME) || die "apt-get download failed"
    if [ "$with_toolchain" = 1 ]; then
        mkdir -p "$debs/toolchain"
        # shellcheck disable=SC2086
        (cd "$debs/toolchain" && apt-get "${o[@]}" download $PN_DEBS_TOOLCHAIN) || die "apt-get download failed"
    fi
    echo "device_check: $(find "$debs" -name '*.deb' | wc -l) packages in $debs ($(du -sh "$debs" | cut -f1))"
}

stage_scenes() {
    local src=$here/../shared/scenes dst=$here/.scenes
    ls "$src"/*.glb >/dev/null 2>&1 || die "no scenes in $src"
    mkdir -p "$dst" || die "cannot create $dst"
    cp "$src"/*.glb "$src"/views.json "$dst"/ || die "cannot copy the scenes"
    [ -f "$src/README.md" ] && cp "$src/README.md" "$dst"/
    echo "device_check: $(ls "$dst"/*.glb | wc -l) scenes in $dst ($(du -sh "$dst" | cut -f1))"
}

# ---- options -------------------------------------------------------------------------------

short=0 build_dir="" out_dir=${OUT:-./device-check-out} device="" device_given=0
size=1024 k=8 reps=3 bench_scenes=$PN_BENCH_SCENES_DEFAULT budget=450
prep="" with_toolchain=0
args="$*"
while [ $# -gt 0 ]; do
    case "$1" in
        --short) short=1 ;;
        --build-dir) build_dir=${2:?--build-dir needs a folder}; shift ;;
        --out) out_dir=${2:?--out needs a folder}; shift ;;
        --device) device=${2:?--device needs a device string}; device_given=1; shift ;;
        --size) size=${2:?}; shift ;;
        --k) k=${2:?}; shift ;;
        --reps) reps=${2:?}; shift ;;
        --scenes) bench_scenes=${2:?}; shift ;;
        --budget) budget=${2:?}; shift ;;
        --fetch-debs) prep="$prep debs" ;;
        --with-toolchain) with_toolchain=1 ;;
        --stage-scenes) prep="$prep scenes" ;;
        --prepare) prep="$prep debs scenes" ;;
        -h|--help) sed -n '2,/^set -u/p' "$0" | sed 's/^# \{0,1\}//' | sed '$d'; exit 0 ;;
        *) die "unknown option '$1' (--help)" ;;
    esac
    shift
done
if [ -n "$prep" ]; then
    case "$prep" in *debs*) fetch_debs "$with_toolchain" ;; esac
    case "$prep" in *scenes*) stage_scenes ;; esac
    exit 0
fi
case "$size$k$reps$budget" in *[!0-9]*) die "--size, --k, --reps and --budget take whole numbers" ;; esac

mkdir -p "$out_dir" || die "cannot create $out_dir"
out_dir=$(cd "$out_dir" && pwd)
setup_log=$out_dir/setup.log
: >"$setup_log"
t_start=$SECONDS

say() { echo "device_check: $*"; echo "$*" >>"$setup_log"; }
elapsed() { echo $((SECONDS - t_start)); }
left() { echo $((budget - (SECONDS - t_start))); }

# Steps: name, result (PASS, FAIL, SKIP, INFO), seconds, note.
step_names=() step_results=() step_secs=() step_notes=()
step_t0=0
step_begin() { step_t0=$SECONDS; say "== $1 ($(elapsed) s in)"; }
step_end() { # name result note
    step_names+=("$1"); step_results+=("$2"); step_secs+=($((SECONDS - step_t0))); step_notes+=("$3")
    say "   $1: $2${3:+ - $3}"
}
# timeout for a step: min(cap, what the budget leaves minus a reserve for the summary)
step_limit() {
    local cap=$1 l
    l=$(($(left) - 15))
    [ "$l" -lt 10 ] && l=10
    [ "$l" -lt "$cap" ] && echo "$l" || echo "$cap"
}
have_timeout=0
command -v timeout >/dev/null && have_timeout=1
run_limited() { # seconds command...
    local s=$1; shift
    if [ "$have_timeout" = 1 ]; then timeout -k 10 "$s" "$@"; else "$@"; fi
}

say "tools/device_check.sh $args"
say "started $(date -u '+%Y-%m-%d %H:%M:%S UTC') on $(uname -n), $(nproc) cores, $(uname -m)"

# ---- 1. carried Debian packages --------------------------------------------------------------

debs=${PN_DEBS:-$here/.debs}
prefix=${PN_PREFIX:-${TMPDIR:-/tmp}/pn-device-prefix}
toolchain_prefix=$prefix-toolchain
arch_lib=x86_64-linux-gnu
unpack() { # deb dir
    if command -v dpkg >/dev/null; then
        dpkg -x "$1" "$2"
    elif command -v ar >/dev/null; then
        local t; t=$(mktemp -d) && (cd "$t" && ar x "$1" && tar -xf data.tar.* -C "$2"); local r=$?; rm -rf "$t"; return $r
    else
        return 1
    fi
}
step_begin "debs"
ndeb=0 nfail=0
if ls "$debs"/*.deb >/dev/null 2>&1; then
    mkdir -p "$prefix"
    for f in "$debs"/*.deb; do
        if unpack "$(cd "$(dirname "$f")" && pwd)/$(basename "$f")" "$prefix" >>"$setup_log" 2>&1; then
            ndeb=$((ndeb + 1)); else nfail=$((nfail + 1)); say "   cannot unpack $f"; fi
    done
    export LD_LIBRARY_PATH="$prefix/usr/lib/$arch_lib:$prefix/lib/$arch_lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
    export PATH="$PATH:$prefix/usr/bin"
    export CMAKE_PREFIX_PATH="$prefix/usr${CMAKE_PREFIX_PATH:+:$CMAKE_PREFIX_PATH}"
    if [ "$nfail" = 0 ]; then step_end debs PASS "$ndeb packages from $debs unpacked into $prefix"
    else step_end debs FAIL "$nfail of $((ndeb + nfail)) packages did not unpack (no dpkg, no ar?)"; fi
else
    step_end debs SKIP "no .deb in $debs: the system's own packages are used"
fi
if ls "$debs"/toolchain/*.deb >/dev/null 2>&1; then
    mkdir -p "$toolchain_prefix"
    for f in "$debs"/toolchain/*.deb; do
        unpack "$(cd "$(dirname "$f")" && pwd)/$(basename "$f")" "$toolchain_prefix" >>"$setup_log" 2>&1 || say "   cannot unpack $f"
    done
    say "   toolchain packages unpacked into $toolchain_prefix (used only where the system lacks the tool)"
fi

# ---- 2. the NVIDIA driver's OpenCL ICD -------------------------------------------------------

step_begin "icd"
for d in /usr/local/nvidia/lib64 /usr/local/nvidia/lib; do
    [ -d "$d" ] && case ":${LD_LIBRARY_PATH:-}:" in *":$d:"*) ;; *) export LD_LIBRARY_PATH="${LD_LIBRARY_PATH:+$LD_LIBRARY_PATH:}$d" ;; esac
done
nv_icd=""
for cand in $( { ldconfig -p 2>/dev/null | awk '/libnvidia-opencl\.so/ {print $NF}';
                 for d in /usr/lib/$arch_lib /usr/lib64 /usr/lib /usr/local/nvidia/lib64 /usr/local/nvidia/lib \
                          /usr/lib/$arch_lib/nvidia/current /run/nvidia/driver/usr/lib/$arch_lib; do
                     ls "$d"/libnvidia-opencl.so* 2>/dev/null; done
                 run_limited 20 find /usr /opt /lib /lib64 -name 'libnvidia-opencl.so*' 2>/dev/null; } | sort -u); do
    [ -e "$cand" ] || continue
    case "$cand" in *libnvidia-opencl.so.1) nv_icd=$cand; break ;; esac
    [ -z "$nv_icd" ] && nv_icd=$cand
done
if [ -z "$nv_icd" ]; then
    step_end icd SKIP "no libnvidia-opencl.so* (ldconfig -p, /usr/lib/$arch_lib, /usr/local/nvidia/lib64): no NVIDIA OpenCL driver"
elif grep -qs "libnvidia-opencl" /etc/OpenCL/vendors/*.icd ${OCL_ICD_VENDORS:+"$OCL_ICD_VENDORS"/*.icd}; then
    step_end icd PASS "$nv_icd, already registered in /etc/OpenCL/vendors"
elif [ "$(id -u)" = 0 ] && mkdir -p /etc/OpenCL/vendors 2>/dev/null && echo "$nv_icd" >/etc/OpenCL/vendors/nvidia.icd 2>/dev/null; then
    step_end icd PASS "$nv_icd, registered as /etc/OpenCL/vendors/nvidia.icd"
else
    # Not root (or /etc read-only): a vendors folder of our own, with the system's ICDs in it too.
    mkdir -p "$prefix/vendors"
    cp /etc/OpenCL/vendors/*.icd "$prefix/vendors/" 2>/dev/null
    echo "$nv_icd" >"$prefix/vendors/nvidia.icd"
    export OCL_ICD_VENDORS=$prefix/vendors
    step_end icd PASS "$nv_icd, registered in OCL_ICD_VENDORS=$prefix/vendors"
fi
command -v nvidia-smi >/dev/null && { nvidia-smi -L 2>&1 | head -8 | sed 's/^/   /' >>"$setup_log"; }

# ---- 3a. devices as the loader sees them -------------------------------------------------------

step_begin "clinfo"
if command -v clinfo >/dev/null; then
    clinfo_out=$(run_limited 60 clinfo -l 2>&1)
    echo "$clinfo_out" | sed 's/^/   /' >>"$setup_log"
    step_end clinfo INFO "$(echo "$clinfo_out" | grep -c 'Device #') device(s)"
else
    clinfo_out=""
    step_end clinfo SKIP "no clinfo (carry it: --fetch-debs); penumbra info lists the devices below"
fi

# ---- 4. build -----------------------------------------------------------------------------------

scenes=""
for s in "$here/../shared/scenes" "$here/.scenes" "${PN_SCENES:-}"; do
    [ -n "$s" ] && ls "$s"/*.glb >/dev/null 2>&1 && { scenes=$(cd "$s" && pwd); break; }
done
: "${build_dir:=$here/build-device}"
# Absolute: the tests run from inside the build tree.
case "$build_dir" in /*) ;; *) build_dir=$PWD/$build_dir ;; esac
build_log=$out_dir/build.log
: >"$build_log"
exe_cli=$build_dir/tools/penumbra exe_cross=$build_dir/tests/test_crossport
exe_golden=$build_dir/tests/test_golden exe_bench=$build_dir/tools/bench_ports
step_begin "build"
if [ -f "$build_dir/CMakeCache.txt" ] && [ -x "$exe_cli" ] && [ -x "$exe_golden" ] && [ -x "$exe_bench" ]; then
    step_end build SKIP "existing build $build_dir used as it is"
else
    missing=""
    cmake_bin=$(command -v cmake || true)
    if [ -z "$cmake_bin" ] && python3 -c 'import cmake' 2>/dev/null; then
        cmake_bin=$(python3 -c 'import cmake, os; print(os.path.join(cmake.CMAKE_BIN_DIR, "cmake"))' 2>/dev/null)
    fi
    toolchain_libs="$toolchain_prefix/usr/lib/$arch_lib:$toolchain_prefix/lib/$arch_lib"
    if [ -z "$cmake_bin" ] && [ -x "$toolchain_prefix/usr/bin/cmake" ]; then
        cmake_bin=$toolchain_prefix/usr/bin/cmake
        export LD_LIBRARY_PATH="${LD_LIBRARY_PATH:+$LD_LIBRARY_PATH:}$toolchain_libs"
        "$cmake_bin" --version >/dev/null 2>&1 || {
            missing="$missing cmake (carried, but it does not run: $(ldd "$cmake_bin" 2>/dev/null | grep 'not found' | awk '{print $1}' | tr '\n' ' '))"
            cmake_bin=""; }
    fi
    [ -z "$cmake_bin" ] && case "$missing" in *cmake*) ;; *) missing="$missing cmake (carry it: --fetch-debs --with-toolchain)" ;; esac
    cc_bin=$(command -v gcc || command -v cc || true)
    cxx_bin=$(command -v g++ || command -v c++ || true)
    [ -z "$cc_bin" ] && missing="$missing gcc (a C compiler: not carried, the image must have one)"
    [ -z "$cxx_bin" ] && missing="$missing g++ (a C++ compiler, for tinygltf: not carried)"
    gen=()
    if command -v ninja >/dev/null; then gen=(-G Ninja)
    elif command -v make >/dev/null; then gen=(-G "Unix Makefiles")
    elif [ -x "$toolchain_prefix/usr/bin/ninja" ]; then gen=(-G Ninja -DCMAKE_MAKE_PROGRAM="$toolchain_prefix/usr/bin/ninja")
    elif [ -x "$toolchain_prefix/usr/bin/make" ]; then gen=(-G "Unix Makefiles" -DCMAKE_MAKE_PROGRAM="$toolchain_prefix/usr/bin/make")
    else missing="$missing ninja-or-make (carry them: --fetch-debs --with-toolchain)"; fi
    [ -z "$scenes" ] && missing="$missing scenes (../shared/scenes, .scenes/ or PN_SCENES: --stage-scenes)"
    if [ -n "$missing" ]; then
        step_end build FAIL "missing:$missing"
    else
        cfg=(-S "$here" -B "$build_dir" "${gen[@]}" -DCMAKE_BUILD_TYPE=Release -DPN_SHARED_SCENES="$scenes"
             -DCMAKE_C_COMPILER="$cc_bin" -DCMAKE_CXX_COMPILER="$cxx_bin")
        if [ -f "$prefix/usr/include/CL/cl.h" ] && [ -e "$prefix/usr/lib/$arch_lib/libOpenCL.so" ]; then
            cfg+=(-DOpenCL_INCLUDE_DIR="$prefix/usr/include" -DOpenCL_LIBRARY="$prefix/usr/lib/$arch_lib/libOpenCL.so")
        fi
        targets=(--target penumbra_cli test_golden bench_ports)
        [ "$short" = 0 ] && targets+=(test_crossport)
        build_once() {
            echo "+ $cmake_bin ${cfg[*]} $*" >>"$build_log"
            run_limited "$(step_limit 400)" "$cmake_bin" "${cfg[@]}" "$@" >>"$build_log" 2>&1 &&
                run_limited "$(step_limit 400)" "$cmake_bin" --build "$build_dir" -j"$(nproc)" "${targets[@]}" >>"$build_log" 2>&1
        }
        if build_once; then
            step_end build PASS "$("$cmake_bin" --version | head -1), $("$cc_bin" --version | head -1), ${gen[1]}, scenes $scenes"
        elif grep -q "Werror\|\[-W" "$build_log"; then
            # A newer compiler's new warning under the library's -Werror: once more with the
            # warnings left as warnings (a launcher appends -Wno-error to every compile).
            launcher=$prefix/cc-no-werror
            mkdir -p "$prefix"
            printf '#!/bin/sh\nexec "$@" -Wno-error\n' >"$launcher" && chmod +x "$launcher"
            if build_once -DCMAKE_C_COMPILER_LAUNCHER="$launcher" -DCMAKE_CXX_COMPILER_LAUNCHER="$launcher"; then
                step_end build PASS "with -Wno-error: this compiler warns where the project's does not (build.log)"
            else
                step_end build FAIL "cmake/compile failed (build.log)"
            fi
        else
            step_end build FAIL "cmake/compile failed (build.log)"
        fi
    fi
fi
export POCL_CACHE_DIR=${POCL_CACHE_DIR:-$build_dir/pocl-cache}
mkdir -p "$POCL_CACHE_DIR" 2>/dev/null

# ---- 3b. devices as the port sees them; the device to use ----------------------------------------

info_out="" mode="" dev_label="" gpu_found=0
step_begin "devices"
if [ -x "$exe_cli" ]; then
    info_quick=$(run_limited 60 "$exe_cli" info --no-build 2>&1 | sed -n '/^OpenCL devices/,$p')
    if echo "$info_quick" | grep -Eq '^  [0-9]+:[0-9]+ +gpu '; then gpu_found=1; fi
    ndev=$(echo "$info_quick" | grep -Ec '^  [0-9]+:[0-9]+ ')
    if [ "$device_given" = 0 ]; then
        if [ "$gpu_found" = 1 ]; then device=gpu; fi
    fi
    if [ "$ndev" = 0 ]; then
        mode="no OpenCL device"
    elif [ "$device_given" = 1 ]; then
        mode="device '$device' (given)"
    elif [ "$gpu_found" = 1 ]; then
        mode="GPU"
    elif echo "$info_quick" | grep -qi "portable computing language"; then
        mode="no GPU: PoCL fallback"
    else
        mode="no GPU: fallback to the port's default device"
    fi
    # The full listing: every device the checks pass is opened (kernels built, numerics probe run).
    info_out=$(run_limited "$(step_limit 240)" "$exe_cli" info 2>&1 | sed -n '/^OpenCL devices/,$p')
    echo "$info_out" | sed 's/^/   /' >>"$setup_log"
    if [ "$ndev" = 0 ]; then
        step_end devices FAIL "no OpenCL device (no GPU ICD and no PoCL)"
    else
        # The line of the device in use: the first GPU, or the given P:D, else the first PoCL CPU.
        dev_type=$(echo "$device" | tr 'A-Z' 'a-z' | sed -nE 's/^(gpu|cpu|accelerator)(:[0-9]+)?$/\1/p')
        if [ -n "$dev_type" ]; then
            nth=$(echo "$device" | sed -nE 's/^[^:]*:([0-9]+)$/\1/p')
            dev_line=$(echo "$info_out" | grep -E "^  [0-9]+:[0-9]+ +$dev_type " | sed -n "$((${nth:-0} + 1))p")
        elif echo "$device" | grep -Eq '^[0-9]+:[0-9]+$'; then dev_line=$(echo "$info_out" | grep -E "^  $device " | head -1)
        elif [ -z "$device" ]; then dev_line=$(echo "$info_out" | grep -i "portable computing language" | grep -E ' cpu ' | head -1)
        else dev_line=$(echo "$info_out" | grep -Fi -- "$device" | head -1); fi
        dev_label=$(echo "$dev_line" | sed -E 's/^  [0-9]+:[0-9]+ +[a-z]+ +//; s/: (accepted|refused).*//')
        if echo "$dev_line" | grep -q ": accepted"; then
            step_end devices PASS "$ndev device(s); using ${device:-the default} = $dev_label, accepted by the port"
        elif [ -n "$dev_line" ]; then
            step_end devices FAIL "the port refuses ${device:-the default device}: $(echo "$dev_line" | sed 's/.*: refused: //')"
        else
            step_end devices INFO "$ndev device(s); ${device:-the default device} is not in the list (see setup.log)"
        fi
    fi
else
    mode="unknown (nothing built)"
    step_end devices SKIP "no penumbra CLI (the build failed)"
fi
dev_arg=()
[ -n "$device" ] && dev_arg=(--cl-device "$device")

# ---- 5. test_crossport and the golden frames on the device ------------------------------------

cross_log=$out_dir/crossport.log golden_log=$out_dir/golden.log
bytes_bad=0
# A step that runs a program: begins it, or records why it is skipped and returns 1.
step_can_run() { # name program seconds-it-needs-at-least
    step_begin "$1"
    if [ ! -x "$2" ]; then step_end "$1" SKIP "not built"; return 1; fi
    if [ "$(left)" -lt "$3" ]; then step_end "$1" SKIP "time budget spent"; return 1; fi
    return 0
}

if [ "$short" = 1 ]; then
    step_begin test_crossport
    step_end test_crossport SKIP "--short (ctest test_crossport runs it in full)"
elif step_can_run test_crossport "$exe_cross" 60; then
    (cd "$build_dir/tests" && { [ -z "$device" ] || export PN_OPENCL_DEVICE="$device"; } &&
        run_limited "$(step_limit 240)" "$exe_cross") >"$cross_log" 2>&1
    rc=$?
    ndiff=$(grep -c "differs in" "$cross_log")
    [ "$ndiff" -gt 0 ] && bytes_bad=1
    last=$(grep -E '^[0-9]+ passed, [0-9]+ failed' "$cross_log" | tail -1)
    if [ "$rc" = 0 ]; then step_end test_crossport PASS "$last"
    elif [ "$rc" = 124 ] || [ "$rc" = 137 ]; then step_end test_crossport FAIL "timed out ($last)"
    else
        nfail=$(grep -c 'CHECK failed\|REQUIRE failed' "$cross_log")
        step_end test_crossport FAIL "${last:-exit $rc}; $ndiff buffer(s) differ; $nfail failed check(s)"
    fi
fi

if step_can_run golden "$exe_golden" 30; then
    only=()
    [ "$short" = 1 ] && only=(--only square)
    (cd "$build_dir/tests" && run_limited "$(step_limit 180)" "$exe_golden" --port opencl "${dev_arg[@]}" "${only[@]}") >"$golden_log" 2>&1
    rc=$?
    nhash=$(grep -c "rendered .*, golden" "$golden_log")
    [ "$nhash" -gt 0 ] && bytes_bad=1
    last="$(grep '^test_golden: ' "$golden_log" | tail -1 | sed 's/^test_golden: //'); $(grep -E '^[0-9]+ passed' "$golden_log" | tail -1)"
    if [ "$rc" = 0 ]; then step_end golden PASS "$last"
    else step_end golden FAIL "$last; $nhash hash(es) differ (exit $rc)"; fi
fi

# ---- 6. benchmark -----------------------------------------------------------------------------------

bench_txt=$out_dir/bench.txt bench_log=$out_dir/bench.log
if step_can_run bench "$exe_bench" 45; then
    if [ "$short" = 1 ]; then
        bargs=(--size 64x48 --k 4 --reps 1 --only spot --algos "reference,gears" --threads "$(nproc)" --no-build-time)
    else
        bargs=(--size "${size}x${size}" --k "$k" --reps "$reps" --only "$bench_scenes" --threads "$(nproc)"
               --cache "$POCL_CACHE_DIR")
    fi
    [ -n "$scenes" ] && bargs+=(--scenes "$scenes")
    echo "+ bench_ports ${bargs[*]} ${dev_arg[*]}" >"$bench_log"
    run_limited "$(step_limit 300)" "$exe_bench" "${bargs[@]}" "${dev_arg[@]}" >"$bench_txt" 2>>"$bench_log"
    rc=$?
    if grep -q "^all frames byte-identical: yes" "$bench_txt" && [ "$rc" = 0 ]; then
        nf=$(grep -c ' failed: ' "$bench_txt")
        step_end bench PASS "$(grep -c ' yes$' "$bench_txt") rows, every frame byte-identical$([ "$nf" -gt 0 ] && echo " ($nf failed the same way on both ports: see the table)")"
    else
        grep -q "^all frames byte-identical: NO" "$bench_txt" && bytes_bad=1
        [ "$rc" = 124 ] || [ "$rc" = 137 ] && note="timed out: the table holds the scenes done" || note="exit $rc"
        step_end bench FAIL "$note; $(grep -c ' NO$' "$bench_txt") row(s) differ (bench.txt, bench.log)"
    fi
fi

# ---- 7. summary --------------------------------------------------------------------------------------

summary=$out_dir/summary.md
failed="" ran_bytes=0 logs=""
for f in "$out_dir"/*; do
    b=$(basename "$f")
    [ "$b" = summary.md ] || logs="$logs $b"
done
for i in "${!step_names[@]}"; do
    [ "${step_results[$i]}" = FAIL ] && failed="$failed ${step_names[$i]}"
    case "${step_names[$i]}" in test_crossport|golden|bench) [ "${step_results[$i]}" = PASS ] && ran_bytes=1 ;; esac
done
{
    echo "# penumbra device check"
    echo
    echo "- run: \`tools/device_check.sh $args\`$([ "$short" = 1 ] && echo ' (short mode)'), $(date -u '+%Y-%m-%d %H:%M UTC'), $(elapsed) s"
    echo "- machine: $(uname -n), $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo 2>/dev/null | cut -d: -f2 | sed 's/^ //')), $(uname -m)"
    if command -v nvidia-smi >/dev/null; then
        echo "- GPU (nvidia-smi): $(nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2>/dev/null | head -2 | tr '\n' ';')"
    fi
    echo "- mode: **$mode**"
    echo "- OpenCL device used: ${dev_label:-?} (device string: ${device:-none, the default of the port})"
    echo
    echo "## Steps"
    echo
    echo "| step | result | s | note |"
    echo "| --- | --- | --- | --- |"
    for i in "${!step_names[@]}"; do
        echo "| ${step_names[$i]} | ${step_results[$i]} | ${step_secs[$i]} | $(echo "${step_notes[$i]}" | sed 's/|/\\|/g') |"
    done
    echo
    echo "## OpenCL devices"
    echo
    echo '```'
    [ -n "$clinfo_out" ] && { echo "clinfo -l:"; echo "$clinfo_out"; echo; }
    echo "${info_out:-penumbra info: not run}"
    echo '```'
    echo
    echo "## Benchmark"
    echo
    echo '```'
    if [ -s "$bench_txt" ]; then cat "$bench_txt"; else echo "not run"; fi
    echo '```'
    for f in "$cross_log" "$golden_log"; do
        if [ -f "$f" ] && grep -q "CHECK failed\|REQUIRE failed" "$f"; then
            echo
            echo "## First failures of $(basename "$f")"
            echo
            echo '```'
            grep "CHECK failed\|REQUIRE failed" "$f" | head -12 | cut -c1-400
            echo '```'
        fi
    done
    echo
    echo "Logs (beside this file):$logs"
    echo
    if [ -z "$failed" ] && [ "$ran_bytes" = 1 ] && [ "$bytes_bad" = 0 ]; then
        echo "device_check: PASS: every step passed; bytes matched on ${dev_label:-the default device} ($mode)"
    else
        [ "$bytes_bad" = 1 ] && bm="BYTES DIFFER" || bm="no byte difference seen"
        echo "device_check: FAIL:${failed:- nothing ran that compares bytes}; $bm ($mode)"
    fi
} >"$summary"
cat "$summary"
tail -1 "$summary" | grep -q "^device_check: PASS" && exit 0
exit 1
