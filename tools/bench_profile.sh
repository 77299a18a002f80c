#!/bin/sh
# Where the shadow-pass time goes: callgrind instruction counts of each algorithm's shadow
# pass and of Embree's, on one scene, one thread, printed as Markdown. make bench appends
# the result to docs/bench/RESULTS.md (issue 5: "if it falls short, profile and say where
# the time goes"). Instruction counts, unlike times, do not move with the machine's load.
#   usage: tools/bench_profile.sh PENUMBRA_BENCH PENUMBRA_CLI SCENES_DIR [SCENE] [SIZE]
# Each algorithm runs in its own valgrind process (penumbra_bench --algos X --lean) with
# collection switched on only inside the shadow pass (src/pn_frame.c pn_shadow, pn_embree_shadow);
# the CLI's --stats gives the predicate counters of the same frame, natively.
# Valgrind emulates no AVX-512: Embree runs its AVX2 code under it (natively it may pick
# AVX-512), so its counts are those of the AVX2 kernels.
set -eu
[ $# -ge 3 ] || { echo "usage: $0 PENUMBRA_BENCH PENUMBRA_CLI SCENES_DIR [SCENE] [SIZE]" >&2; exit 2; }
bench=$1 cli=$2 scenes=$3 scene=${4:-stanford_dragon} size=${5:-64}
k=16
if ! command -v valgrind >/dev/null 2>&1 || ! command -v callgrind_annotate >/dev/null 2>&1; then
  echo "## Where the time goes (callgrind)"
  echo
  echo "Not measured: valgrind is not installed (apt install valgrind)."
  exit 0
fi
if [ ! -f "$scenes/$scene.glb" ]; then
  echo "## Where the time goes (callgrind)"
  echo
  echo "Not measured: $scenes/$scene.glb is missing."
  exit 0
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

for a in reference GEARS raytrace embree; do
  case $a in
    embree) sel=raytrace,embree toggle=pn_embree_shadow ;; # some frame must give the G-buffer
    *) sel=$a toggle=pn_shadow ;;
  esac
  echo "bench_profile: callgrind $a ($scene ${size}x$size)" >&2
  valgrind --tool=callgrind --callgrind-out-file="$work/$a.cg" --collect-atstart=no --toggle-collect="$toggle" \
    "$bench" --only "$scene" --size "$size" --k "$k" --reps 1 --threads 1 --ports 1 --lean --sweep-scenes none \
    --algos "$sel" --scenes "$scenes" --out "$work/out_$a" > /dev/null 2> "$work/$a.log" ||
    { cat "$work/$a.log" >&2; exit 1; }
  callgrind_annotate --inclusive=no --threshold=100 "$work/$a.cg" > "$work/$a.self" 2>/dev/null
  callgrind_annotate --inclusive=yes --threshold=100 "$work/$a.cg" > "$work/$a.incl" 2>/dev/null
  case $a in
    embree) ;;
    *) "$cli" render "$scenes/$scene.glb" --algo "$(echo "$a" | tr 'A-Z' 'a-z')" --size "${size}x$size" --k "$k" \
         --threads 1 --out "$work/$a.png" --stats "$work/$a.json" 2> /dev/null ;;
  esac
done

# "1,234 (5.6%)  /path/file.c:function [/path/binary]" -> Ir of a line matching a pattern.
ir_of() { # file pattern
  awk -v pat="$2" '$0 ~ pat { gsub(",", "", $1); print $1; exit }' "$1"
}
total_of() { ir_of "$1" "PROGRAM TOTALS"; }
. "$(dirname "$0")/pn_stats.sh" # json FILE KEY
lit=$(json "$work/reference.json" lit_pixels)
samples=$((lit * k * k))

echo "## Where the time goes (callgrind)"
echo
echo "Instruction counts (callgrind \`Ir\`) of one shadow pass: $scene at ${size}x$size, k = $k, one thread; $lit lit"
echo "pixels, $samples light samples. Written by tools/bench_profile.sh; each row is its own valgrind run with"
echo "collection on only inside the pass. Predicate calls: \`pn_stats.shadow_candidates\` of the same frame (for"
echo "raytrace, ray-triangle tests). Valgrind has no AVX-512, so Embree's rows count its AVX2 kernels, and our"
echo "library here is compiled for the compiler's default target (x86-64: SSE2), not the timed build's -march=native."
echo
echo "| shadow pass | instructions (millions) | per lit pixel | per light sample | predicate calls per lit pixel | instructions per predicate call |"
echo "| --- | ---: | ---: | ---: | ---: | ---: |"
for a in reference GEARS raytrace; do
  ir=$(total_of "$work/$a.self")
  cand=$(json "$work/$a.json" shadow_candidates)
  awk -v a="$a" -v ir="$ir" -v lit="$lit" -v s="$samples" -v c="$cand" 'BEGIN {
    printf "| %s | %.0f | %.0f | %.0f | %.1f | %.0f |\n", a, ir / 1e6, ir / lit, ir / s, c / lit, ir / c }'
done
for api in rtcOccluded1 rtcOccluded16; do
  ir=$(ir_of "$work/embree.incl" ":$api ")
  awk -v a="Embree $api" -v ir="${ir:-0}" -v lit="$lit" -v s="$samples" 'BEGIN {
    printf "| %s | %.0f | %.0f | %.0f | n/a | n/a |\n", a, ir / 1e6, ir / lit, ir / s }'
done
echo
echo "Where each pass spends its instructions (self cost by source file and function; the kernels are inlined, so"
echo "a kernel header names the code that came from it, the function the loop it was inlined into):"
echo
for a in reference GEARS raytrace embree; do
  tot=$(total_of "$work/$a.self")
  echo "- **$a**:"
  awk -v tot="$tot" '
    /file:function/ { body = 1; next }
    body && /^-+$/ { if (n) exit; next }
    body && $1 ~ /^[0-9,]+$/ {
      ir = $1; gsub(",", "", ir)
      line = $0; sub(/^ *[0-9,]+ +\([ 0-9.]+%\) +/, "", line)
      split(line, w, " "); where = w[1]; sub(".*/", "", where)
      if (where ~ /^\?\?\?/) { bin = line; sub(/.*\[/, "", bin); sub(/\].*/, "", bin); sub(".*/", "", bin); where = bin " (no symbols)" }
      if (n < 6 && ir / tot >= 0.01) { printf "  %s %.1f%%;", where, 100 * ir / tot; n++ }
    }
    END { print "" }' "$work/$a.self"
done
