#!/bin/sh
# The exact algorithms' shadow passes per scene, the quantities issue 14 asks for where
# GEARS misses the reference: callgrind instructions per lit pixel (GEARS' also those of its
# per-pixel step, the pass gears_masks; the rest is its per-frame set-up), boxes tested per
# lit pixel and predicate calls per lit pixel, printed as Markdown.
#   usage: tools/exact_profile.sh PENUMBRA_CLI SCENES_DIR [SIZE] [SCENE ...]
# Each (scene, algorithm) is one valgrind run of the CLI with collection on only inside
# the shadow pass (src/pn_frame.c pn_shadow, kept out of line for this), one thread,
# k = 16; the counters come from the same frame's --stats. A scene is a built-in's name or
# a .glb in SCENES_DIR (from its view when SCENES_DIR/views.json has one). Instruction
# counts do not move with the machine's load; they are those of the library as the CLI was
# built (use a default-target build: valgrind has no AVX-512).
set -eu
[ $# -ge 2 ] || { echo "usage: $0 PENUMBRA_CLI SCENES_DIR [SIZE] [SCENE ...]" >&2; exit 2; }
cli=$1 scenes=$2 size=${3:-128}
[ $# -ge 3 ] && shift 3 || shift $#
[ $# -gt 0 ] || set -- square spheres elongated-cube thin room canopy colonnade spot chess_set stanford_bunny \
  cad_infineon_easypim2b grey_white_room happy_buddha_100k stanford_dragon copper_beech
command -v valgrind >/dev/null 2>&1 || { echo "exact_profile: valgrind is not installed" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

. "$(dirname "$0")/pn_stats.sh" # json FILE KEY

echo "| scene | lit pixels | reference: instructions / lit pixel | boxes / lit pixel | predicate calls / lit pixel | GEARS: instructions / lit pixel | of which the per-pixel step | boxes / lit pixel | cell triangles / lit pixel | predicate calls / lit pixel | GEARS vs reference (instructions) |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
for s in "$@"; do
  src=$(scene_src "$scenes" "$s")
  for a in reference gears; do
    echo "exact_profile: $s $a ${size}x$size" >&2
    # shellcheck disable=SC2086
    valgrind --tool=callgrind --callgrind-out-file="$work/$a.cg" --collect-atstart=no --toggle-collect=pn_shadow \
      "$cli" render $src --algo $a --size "${size}x$size" --k 16 --threads 1 --out "$work/$a.png" \
      --stats "$work/$a.json" > /dev/null 2> "$work/$a.log" || { cat "$work/$a.log" >&2; exit 1; }
    callgrind_annotate --inclusive=yes "$work/$a.cg" 2>/dev/null |
      awk '/PROGRAM TOTALS/ { gsub(",", "", $1); t = $1 }
           /:pn_sc_gears_masks / { gsub(",", "", $1); m = $1 }
           END { print t + 0, m + 0 }' > "$work/$a.ir"
  done
  awk -v s="$s" -v lit="$(json "$work/reference.json" lit_pixels)" \
      -v ri="$(cut -d' ' -f1 "$work/reference.ir")" -v rn="$(json "$work/reference.json" shadow_nodes)" \
      -v rc="$(json "$work/reference.json" shadow_candidates)" \
      -v gi="$(cut -d' ' -f1 "$work/gears.ir")" -v gm="$(cut -d' ' -f2 "$work/gears.ir")" -v gn="$(json "$work/gears.json" shadow_nodes)" \
      -v ga="$(json "$work/gears.json" gears_assignments)" -v gc="$(json "$work/gears.json" shadow_candidates)" 'BEGIN {
    if (lit == 0) lit = 1
    printf "| %s | %d | %.0f | %.1f | %.1f | %.0f | %.0f | %.1f | %.0f | %.1f | %.2fx |\n", s, lit, ri / lit, rn / lit,
           rc / lit, gi / lit, gm / lit, gn / lit, ga / lit, gc / lit, ri / gi }'
done
