# pn_stats.sh - shell helpers the profiling scripts share (tools/bench_profile.sh,
# tools/exact_profile.sh, tools/callgrind_frames.sh), sourced, not run.

# scene_src SCENES_DIR NAME: the CLI's scene arguments for NAME: SCENES_DIR/NAME.glb, else
# the built-in NAME; with its view when SCENES_DIR/views.json has an entry for NAME.
scene_src() {
  if [ -f "$1/$2.glb" ]; then printf '%s' "$1/$2.glb"; else printf '%s' "--builtin $2"; fi
  if grep -q "\"$2\"[[:space:]]*:" "$1/views.json" 2>/dev/null; then printf ' --view %s --views %s' "$2" "$1/views.json"; fi
  echo
}

# json FILE KEY: the number the CLI's --stats JSON gives KEY (its first occurrence), 0 when
# the key is absent.
json() {
  v=$(sed -n "s/.*\"$2\": \([0-9.]*\).*/\1/p" "$1" | head -n 1)
  echo "${v:-0}"
}
