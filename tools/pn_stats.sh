# pn_stats.sh - shell helpers the profiling scripts share (tools/bench_profile.sh,
# tools/exact_profile.sh), sourced, not run.

# json FILE KEY: the number the CLI's --stats JSON gives KEY (its first occurrence), 0 when
# the key is absent.
json() {
  v=$(sed -n "s/.*\"$2\": \([0-9.]*\).*/\1/p" "$1" | head -n 1)
  echo "${v:-0}"
}
