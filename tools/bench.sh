#!/bin/sh
# Runs the benchmark and draws its plots: what `make bench` and `make bench-quick` call, and
# what the bench_quick ctest runs so that the quick path cannot rot.
#   usage: tools/bench.sh full|quick PENUMBRA_BENCH OUT_DIR [SCENES_DIR]
# full:  every built-in scene and every .glb in SCENES_DIR, the paper-style sweeps, the
#        gallery; OUT_DIR (docs/bench) is emptied first, so it is regenerated from scratch.
# quick: a small subset with every code path (see --quick in tools/bench/main.c).
# full also appends tools/bench_profile.sh's callgrind table (where the time goes).
# Plots and the gallery are drawn by gnuplot from OUT_DIR/plots.gp when gnuplot is
# installed (make bench installs it); without it the tables are still written.
set -eu
[ $# -ge 3 ] || { echo "usage: $0 full|quick PENUMBRA_BENCH OUT_DIR [SCENES_DIR]" >&2; exit 2; }
mode=$1 bin=$2 out=$3 scenes=${4:-${PN_SCENES_DIR:-}}
case "$mode" in full) flag= ;; quick) flag=--quick ;; *) echo "$0: mode must be full or quick" >&2; exit 2 ;; esac
[ -x "$bin" ] || { echo "$0: $bin is not an executable (build the penumbra_bench target)" >&2; exit 1; }
case "$out" in ''|/|.|..) echo "$0: refusing to empty '$out'" >&2; exit 2 ;; esac

label=
root=$(dirname "$0")/..
if rev=$(git -C "$root" rev-parse --short HEAD 2>/dev/null); then
  label="commit $rev"
  git -C "$root" diff --quiet HEAD -- . ':!docs/bench' 2>/dev/null || label="$label with local changes"
fi
rm -rf "$out"
mkdir -p "$out"
# The OpenCL port's kernels (PoCL) are compiled once and cached in the build directory.
POCL_CACHE_DIR=${POCL_CACHE_DIR:-$(cd "$(dirname "$bin")/.." && pwd)/pocl-cache}
export POCL_CACHE_DIR
set -- --out "$out"
[ -n "$scenes" ] && set -- "$@" --scenes "$scenes"
[ -n "$flag" ] && set -- "$@" "$flag"
[ -n "$label" ] && set -- "$@" --label "$label"
"$bin" "$@" # prints the tables (the text of RESULTS.md); progress goes to stderr
if command -v gnuplot >/dev/null 2>&1; then
  (cd "$out" && gnuplot plots.gp)
else
  echo "bench: gnuplot not found: no plots or gallery (apt install gnuplot-nox)" >&2
fi
rm -rf "$out/work"
# What a context costs, per algorithm (the library's carve: no timing, the same on any machine).
mem="$(dirname "$bin")/penumbra_memory"
if [ -x "$mem" ]; then
  echo >> "$out/RESULTS.md"
  "$mem" >> "$out/RESULTS.md"
fi
if [ "$mode" = full ]; then
  # Where the time goes: callgrind instruction counts of every shadow pass (valgrind). Valgrind
  # cannot run AVX-512, so make bench hands a build for the compiler's default target in
  # PN_PROFILE_BENCH when the timed build is -march=native.
  pbin=${PN_PROFILE_BENCH:-$bin}
  sh "$(dirname "$0")/bench_profile.sh" "$pbin" "$(dirname "$pbin")/penumbra" "$scenes" >> "$out/RESULTS.md"
fi
echo "bench: wrote $out/RESULTS.md" >&2
