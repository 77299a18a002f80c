#!/bin/sh
# Callgrind instructions (Ir) of one whole frame per (scene, algorithm), printed as Markdown,
# to check that a refactor moved each algorithm's frame cost by less than 1%.
#   usage: tools/callgrind_frames.sh [--compare BEFORE_CLI] PENUMBRA_CLI SCENES_DIR [SIZE] [SCENE ...]
# Defaults: SIZE 256, scenes spot chess_set. A scene is a .glb in SCENES_DIR, else a built-in's
# name; a scene with an entry in SCENES_DIR/views.json is rendered from that view (--view),
# the others from the CLI's default view; both binaries get the same flags. With --compare,
# BEFORE_CLI is the baseline and the table has before, after (PENUMBRA_CLI) and after/before;
# rows outside 0.99-1.01 are marked. ALGOS="gears mcsm" limits the algorithms (default: every
# one the CLI lists); BEFORE_FLAGS and AFTER_FLAGS add render options to the baseline's and
# to PENUMBRA_CLI's runs (the same CLI twice with two settings: BEFORE_FLAGS="--gears-pairs
# 262144" AFTER_FLAGS="--gears-pairs 0"). Each run: one thread, collection on only inside
# pn_render_with (the scalar pn_render is a tail jump to it in src/pn_frame.c, so the toggle
# must name pn_render_with), the count from the out file's totals line. Instruction counts do
# not move with the machine's load; build both CLIs with the same flags and no -march=native
# (valgrind has no AVX-512).
set -eu
usage="usage: $0 [--compare BEFORE_CLI] PENUMBRA_CLI SCENES_DIR [SIZE] [SCENE ...]"
before=
if [ "${1:-}" = --compare ]; then [ $# -ge 2 ] || { echo "$usage" >&2; exit 2; }; before=$2; shift 2; fi
[ $# -ge 2 ] || { echo "$usage" >&2; exit 2; }
cli=$1 scenes=$2 size=${3:-256}
if [ $# -ge 3 ]; then shift 3; else shift $#; fi
[ $# -gt 0 ] || set -- spot chess_set
command -v valgrind >/dev/null 2>&1 || { echo "callgrind_frames: valgrind is not installed" >&2; exit 1; }
work=$(mktemp -d)
. "$(dirname "$0")/pn_stats.sh" # scene_src SCENES_DIR NAME
trap 'rm -rf "$work"' EXIT

# The algorithms as the CLI's help lists them ("algorithms: ..."); the fallback is the list of 195dced.
algos=${ALGOS:-$("$cli" --help 2>&1 | sed -n 's/^algorithms: //p' | head -n 1)}
[ -n "$algos" ] || algos="reference gears raytrace srt occtex mcsm wedges"

# frame_ir CLI SCENE ALGO [FLAGS]: the Ir of the frame, on stdout.
frame_ir() {
  src=$(scene_src "$scenes" "$2")
  echo "callgrind_frames: $1 $2 $3 ${size}x$size ${4:-}" >&2
  rm -f "$work/cg.out"
  # shellcheck disable=SC2086
  valgrind --tool=callgrind --callgrind-out-file="$work/cg.out" --collect-atstart=no \
    --toggle-collect=pn_render_with "$1" render $src --algo "$3" --size "${size}x$size" \
    --threads 1 ${4:-} --out "$work/frame.png" > /dev/null 2> "$work/log" || { cat "$work/log" >&2; exit 1; }
  awk '/^(summary|totals):/ { t = $2 } END { if (t == "") exit 1; print t }' "$work/cg.out"
}

if [ -z "$before" ]; then
  echo "| scene | algorithm | Ir |"
  echo "| --- | --- | ---: |"
else
  echo "| scene | algorithm | Ir before | Ir after | after / before |"
  echo "| --- | --- | ---: | ---: | ---: |"
fi
for s in "$@"; do
  for a in $algos; do
    after_ir=$(frame_ir "$cli" "$s" "$a" "${AFTER_FLAGS:-}")
    if [ -z "$before" ]; then echo "| $s | $a | $after_ir |"; continue; fi
    before_ir=$(frame_ir "$before" "$s" "$a" "${BEFORE_FLAGS:-}")
    awk -v s="$s" -v a="$a" -v b="$before_ir" -v n="$after_ir" 'BEGIN {
      r = n / b; flag = (r < 0.99 || r > 1.01) ? " **outside 1%**" : ""
      printf "| %s | %s | %.0f | %.0f | %.4f%s |\n", s, a, b, n, r, flag }'
  done
done
