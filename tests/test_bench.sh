#!/bin/sh
# bench_quick: runs `make bench-quick`'s path (tools/bench.sh quick) on the test build so the
# benchmark cannot rot, and checks the report's shape and its correctness columns. It
# checks no timing: speed is only ever printed, never asserted. Embree and gnuplot are
# optional here (make test does not install them); the report must say so when absent.
# usage: test_bench.sh BENCH_SH PENUMBRA_BENCH SCENES_DIR WORK_DIR
set -u
script=$1 bin=$2 scenes=$3 work=$4
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*" >&2; }
check() { if "$@"; then ok; else bad "$*"; fi; }

sh "$script" quick "$bin" "$work" "$scenes" > "$work.stdout" 2> "$work.stderr"
r=$?
check test $r -eq 0
[ $r -eq 0 ] || cat "$work.stderr" >&2
md=$work/RESULTS.md
check test -s "$md"
for s in square elongated-cube room canopy colonnade; do
  check grep -q "^| $s | " "$md"
done
# The interior and the tree, each with its view from views.json: the room's view has no ground
# plane (139,899 triangles as in the file), the tree's has one (+2).
if [ -f "$scenes/grey_white_room.glb" ]; then
  check grep -q '^| grey_white_room | 139899 | ' "$md"
  check grep -q '^| copper_beech | 187310 | ' "$md"
fi
# The summary, and the baselines beside every algorithm: a summary row each, and accuracy rows
# with the gross columns (RMSE, p99, max, gross brighter, gross darker, wrong pixels).
check grep -q '^## Summary: every algorithm on every scene' "$md"
for a in reference GEARS MCSM 'reference k=4' 'reference k=8' PCSS; do
  check grep -q "^| $a | [0-9]* | [0-9.]* (" "$md"
done
for a in 'reference k=4' 'reference k=8' PCSS MCSM; do
  check grep -Eq "^\| square \| $a \| [0-9.]+ \| [0-9.]+ \| [0-9.]+ \| [0-9.]+% \| [0-9.]+% \| [0-9.]+% \| " "$md"
done
if [ -f "$scenes/spot.glb" ]; then
  check grep -q '^| spot | ' "$md"
  check grep -q '^| spot | GEARS ms |' "$md"        # a sweep table row
fi
for section in '## Headline' '## Per port' '## Embree 3 baseline' '## Cost vs output resolution' \
               '## Cost vs mask resolution' '## Cost vs light size' '## Cost vs GEARS grid' \
               '## GEARS grid efficiency' '## Memory' '## Accuracy' '## Gallery' \
               '## Monte Carlo shadow maps' '### MCSM: convergence' '### MCSM: light leaks on closed-box' \
               '### MCSM: cost against the depth-layer' '### MCSM: cost against the image size' \
               "### MCSM: the issue's goal"; do
  check grep -q "^$section" "$md"
done
# MCSM (when compiled in): a claims row per scene, its error heat map, and the leak table's
# closed-box, a scene of that table only.
if ! grep -q '^| square | MCSM | n/a | n/a | n/a | not compiled in |' "$md"; then
  for s in square elongated-cube; do
    check grep -q "^| $s | default (3 layers, hierarchical" "$md"
    check grep -q "^| $s | 2 layers, hierarchical | [0-9]" "$md"
    check grep -q "(mc_heat_$s.png)" "$md"
    check test -s "$work/mc_heat_$s.png"
  done
  check grep -q '^### MCSM: where the default errs' "$md"
  check grep -q '^| closed-box | MCSM | 3 layers (default) | [0-9]' "$md"
fi
check test "$(grep -c '^| closed-box | [0-9]' "$md")" -eq 0
# Exact algorithms match the reference byte for byte, and our recomputed masks reproduce it.
check grep -q 'exact: byte-identical' "$md"
check test "$(grep -c 'DIFFERS' "$md")" -eq 0
check test "$(grep -c '| \*\*no\*\* |' "$md")" -eq 0
# Embree: either measured, or the report says why not.
if grep -q 'Embree baseline unavailable' "$md"; then
  ok
else
  check grep -q 'rtcOccluded' "$md"
  check test "$(grep -c '^| [a-z-]* | 16 | [0-9]' "$md")" -ge 3   # mask agreement rows
fi
if command -v gnuplot >/dev/null 2>&1; then
  for p in speedup sweep_resolution sweep_k sweep_light sweep_grid mc_convergence; do
    check test -s "$work/$p.png"
  done
  [ -f "$scenes/spot.glb" ] && check test -s "$work/gallery/spot.png"
  check test -s "$work/gallery/canopy.png"
fi
check test ! -d "$work/work"
echo "bench_quick: $pass passed, $fail failed"
test $fail -eq 0
