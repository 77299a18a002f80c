#!/bin/sh
# GEARS' grid resolution against its wall time on every scene, beside the reference's, for
# issue 51's question whether GEARS' default configuration is the fastest it can be: per
# scene the shadow pass's milliseconds (the CLI's --stats ms_shadow) of the reference and
# of GEARS at each grid, medians of REPS rounds, printed as Markdown.
#   usage: tools/gears_grid_sweep.sh PENUMBRA_CLI SCENES_DIR [SIZE] [REPS] [SCENE ...]
# A round runs the reference, then GEARS at every grid (32 64 128 256, or $GRIDS), one after
# the other, so that the machine's drift falls on every column alike; k = 16, 2 threads
# ($THREADS). A scene is a built-in's name or a .glb in SCENES_DIR, from its view when
# SCENES_DIR/views.json has one. The default grid is the one the CLI's stats name for a frame
# without --grid (PN_GEARS_GRID_DEFAULT, include/penumbra/config.h); it joins the grids.
set -eu
[ $# -ge 2 ] || { echo "usage: $0 PENUMBRA_CLI SCENES_DIR [SIZE] [REPS] [SCENE ...]" >&2; exit 2; }
cli=$1 scenes=$2 size=${3:-512} reps=${4:-3}
[ $# -ge 4 ] && shift 4 || shift $#
[ $# -gt 0 ] || set -- square spheres elongated-cube thin room canopy colonnade spot chess_set stanford_bunny \
  cad_infineon_easypim2b grey_white_room copper_beech happy_buddha_100k stanford_dragon
grids=${GRIDS:-32 64 128 256}
threads=${THREADS:-2}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

. "$(dirname "$0")/pn_stats.sh" # scene_src, json

# median FILE: the median of the numbers in FILE, one a line
median() {
  sort -g "$1" | awk '{ v[NR] = $1 } END { if (NR % 2) print v[(NR + 1) / 2]; else print (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}

# The library's default grid, as a frame without --grid reports it (gears_grid).
"$cli" render --builtin square --algo gears --size 8x8 --out "$work/x.png" --stats "$work/st.json" >/dev/null 2>&1
dg=$(json "$work/st.json" gears_grid)
case " $grids " in *" $dg "*) ;; *) grids="$grids $dg" ;; esac

head="| scene | reference ms |"
rule="| --- | ---: |"
for g in $grids; do
  head="$head grid $g ms |"
  rule="$rule ---: |"
done
echo "$head fastest grid | grid $dg (default) vs the fastest | GEARS (grid $dg) vs reference | GEARS (fastest grid) vs reference |"
echo "$rule ---: | ---: | ---: | ---: |"
for s in "$@"; do
  src=$(scene_src "$scenes" "$s")
  rm -f "$work"/*.ms
  r=1
  while [ "$r" -le "$reps" ]; do
    echo "gears_grid_sweep: $s round $r" >&2
    for a in reference $grids; do
      if [ "$a" = reference ]; then algo="--algo reference"; else algo="--algo gears --grid $a"; fi
      # shellcheck disable=SC2086 # src and algo are several arguments
      "$cli" render $src $algo --size "${size}x$size" --k 16 --threads "$threads" --out "$work/x.png" \
        --stats "$work/st.json" >/dev/null
      json "$work/st.json" ms_shadow >>"$work/$a.ms"
    done
    r=$((r + 1))
  done
  ref=$(median "$work/reference.ms")
  row="| $s | $ref |"
  best= bestg=
  for g in $grids; do
    m=$(median "$work/$g.ms")
    row="$row $m |"
    if [ -z "$best" ] || awk "BEGIN { exit !($m < $best) }"; then best=$m bestg=$g; fi
  done
  d=$(median "$work/$dg.ms")
  echo "$row $bestg | $(awk "BEGIN { printf \"%.2fx\", $d / $best }") | $(awk "BEGIN { printf \"%.2fx\", $ref / $d }") | $(awk "BEGIN { printf \"%.2fx\", $ref / $best }") |"
done
