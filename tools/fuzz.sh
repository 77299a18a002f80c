#!/bin/sh
# make fuzz: libFuzzer campaigns over every fuzz target (fuzz/README.md, docs/fuzz.md).
#
#   tools/fuzz.sh                 build every target with ASan + UBSan (clang, -DPN_FUZZ=ON),
#                                 run each for FUZZ_MINUTES on a scratch copy of its corpus,
#                                 minimize what it finds, print the table
#   tools/fuzz.sh merge TARGET    after a run: the scratch corpus's inputs that add coverage
#                                 over fuzz/corpus/TARGET, listed (smallest first) for copying
#                                 a handful back by hand
#
# Environment:
#   FUZZ_MINUTES   minutes per target (default 10)
#   FUZZ_TARGETS   targets to run, in order (default: every target, ALL below; a target
#                  the build cannot make, gltf without tinygltf or crossport without OpenCL,
#                  is reported as not built)
#   FUZZ_BUILD     CMake build directory of the clang build (default build/fuzz-clang,
#                  inside the ignored build/ beside the gcc build)
#   FUZZ_SCRATCH   scratch root (default /tmp/penumbra-fuzz): per target corpus/ (the copy
#                  libFuzzer grows), art/ (findings), min/ (minimized findings), fuzz.log
#   FUZZ_JOBS      build parallelism (default 2)
#
# Each target runs with -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1, so
# one finding does not end the campaign: every crash, timeout or OOM is saved in art/ and
# the run goes on. Findings are minimized (-minimize_crash=1) into min/, and the first
# failure line of each (FUZZ_CHECK, sanitizer report) goes into findings.txt.
set -eu

ROOT=$(cd "$(dirname "$0")/.." && pwd)
# Every target (fuzz/CMakeLists.txt builds those the configuration can make).
ALL="scene gears culls tables srt gltf crossport"
MINUTES=${FUZZ_MINUTES:-10}
TARGETS=${FUZZ_TARGETS:-$ALL}
BUILD=${FUZZ_BUILD:-build/fuzz-clang}
SCRATCH=${FUZZ_SCRATCH:-/tmp/penumbra-fuzz}
JOBS=${FUZZ_JOBS:-2}
case "$BUILD" in /*) ;; *) BUILD="$ROOT/$BUILD" ;; esac

case "$MINUTES" in
  ''|*[!0-9]*) echo "fuzz.sh: FUZZ_MINUTES must be a whole number of minutes, not '$MINUTES'" >&2; exit 2 ;;
esac
for t in $TARGETS; do
  case " $ALL " in *" $t "*) ;;
    *) echo "fuzz.sh: unknown target '$t' ($ALL)" >&2; exit 2 ;;
  esac
done

# The environment a target runs in: PoCL needs a cache directory, and keeps allocations
# until exit (no leak checking for crossport).
run_env() {
  if [ "$1" = crossport ]; then
    mkdir -p "$SCRATCH/pocl-cache"
    echo "POCL_CACHE_DIR=$SCRATCH/pocl-cache ASAN_OPTIONS=detect_leaks=0"
  else
    echo "ASAN_OPTIONS=detect_leaks=1"
  fi
}
input_timeout() { [ "$1" = crossport ] && echo 60 || echo 10; }

if [ "${1:-}" = merge ]; then
  t=${2:?usage: tools/fuzz.sh merge TARGET}
  bin="$BUILD/fuzz/fuzz_$t"
  [ -x "$bin" ] || { echo "fuzz.sh: $bin not built (run make fuzz first)" >&2; exit 1; }
  [ -d "$SCRATCH/$t/corpus" ] || { echo "fuzz.sh: no scratch corpus $SCRATCH/$t/corpus" >&2; exit 1; }
  out="$SCRATCH/$t/merge"
  rm -rf "$out" && mkdir -p "$out"
  cp "$ROOT/fuzz/corpus/$t/"* "$out/"
  # With the checked-in corpus already in the output directory, -merge=1 adds only inputs
  # that reach features it does not; -use_counters=0 makes the features edges (not hit
  # count buckets), so the list is the inputs that reach new code, not a few hundred.
  env $(run_env "$t") "$bin" -merge=1 -use_counters=0 -timeout="$(input_timeout "$t")" "$out" "$SCRATCH/$t/corpus" \
      > "$SCRATCH/$t/merge.log" 2>&1 || { tail -20 "$SCRATCH/$t/merge.log" >&2; exit 1; }
  grep -E 'MERGE-OUTER: [0-9]+ new files' "$SCRATCH/$t/merge.log" || true
  echo "inputs adding coverage over fuzz/corpus/$t (smallest first); copy a handful, e.g. as cov-<name>:"
  for f in "$out"/*; do
    b=$(basename "$f")
    [ -e "$ROOT/fuzz/corpus/$t/$b" ] || echo "$(wc -c < "$f") $f"
  done | sort -n | awk '{ printf "  %6d bytes  %s\n", $1, $2 }'
  exit 0
fi

echo "fuzz.sh: building $TARGETS with clang, ASan + UBSan, in $BUILD" >&2
mkdir -p "$BUILD"
CC=clang CXX=clang++ cmake -S "$ROOT" -B "$BUILD" -DPN_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    > "$BUILD/fuzz-configure.log" 2>&1 || { cat "$BUILD/fuzz-configure.log" >&2; exit 1; }
built=""
for t in $TARGETS; do
  if cmake --build "$BUILD" -j "$JOBS" --target "fuzz_$t" > "$BUILD/fuzz-build-$t.log" 2>&1; then
    built="$built $t"
  else
    echo "fuzz.sh: fuzz_$t did not build (see $BUILD/fuzz-build-$t.log)" >&2
    tail -5 "$BUILD/fuzz-build-$t.log" >&2
  fi
done

COMMIT=$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)
DIRTY=$(git -C "$ROOT" status --porcelain --untracked-files=no 2>/dev/null | grep -q . && echo "+dirty" || true)
DATE=$(date -u +%Y-%m-%d)
mkdir -p "$SCRATCH"
SUMMARY="$SCRATCH/summary.md"
{
  echo "| date | commit | target | minutes | executions | cov | ft | findings |"
  echo "| --- | --- | --- | --- | --- | --- | --- | --- |"
} > "$SUMMARY"

for t in $TARGETS; do
  case " $built " in *" $t "*) ;; *)
    echo "| $DATE | $COMMIT$DIRTY | $t | - | not built | - | - | - |" >> "$SUMMARY"; continue ;;
  esac
  bin="$BUILD/fuzz/fuzz_$t"
  d="$SCRATCH/$t"
  rm -rf "$d" && mkdir -p "$d/corpus" "$d/art" "$d/min"
  cp "$ROOT/fuzz/corpus/$t/"* "$d/corpus/"
  # fuzz_culls reads fuzz_crossport's input format: its corpus seeds culls too.
  [ "$t" = culls ] && cp "$ROOT/fuzz/corpus/crossport/"* "$d/corpus/"
  secs=$((MINUTES * 60))
  echo "fuzz.sh: fuzz_$t for $MINUTES min on a copy of fuzz/corpus/$t ($d)" >&2
  rc=0
  # The campaign stops itself at max_total_time; timeout(1) is the backstop for a hung
  # fork server (five minutes of grace for the last job and the corpus merge).
  env $(run_env "$t") timeout -k 30 $((secs + 300)) "$bin" -fork=1 -ignore_crashes=1 \
      -ignore_timeouts=1 -ignore_ooms=1 -timeout="$(input_timeout "$t")" -rss_limit_mb=4096 \
      -max_total_time="$secs" -print_final_stats=1 -artifact_prefix="$d/art/" "$d/corpus" \
      > "$d/fuzz.log" 2>&1 || rc=$?

  # Fork mode: the parent prints "#N: cov: C ft: F corp: ... time: Ts job: J" per job;
  # without fork, "#N ... cov: C ft: F" and stat::number_of_executed_units in the final
  # stats. The last line with cov: gives coverage; executions the larger of the two.
  stats=$(awk '
    /^#[0-9]+/ && / cov: / {
      n = $1; gsub(/[^0-9]/, "", n); execs = n + 0
      for (i = 1; i < NF; i++) { if ($i == "cov:") cov = $(i + 1); if ($i == "ft:") ft = $(i + 1) }
    }
    /^stat::number_of_executed_units:/ { if ($2 + 0 > units) units = $2 + 0 }
    END {
      if (units > execs) execs = units
      printf "%s %s %s\n", (execs == "" ? "?" : execs), (cov == "" ? "?" : cov), (ft == "" ? "?" : ft)
    }' "$d/fuzz.log")
  set -- $stats
  execs=$1 cov=$2 ft=$3
  elapsed=$(awk '/^#[0-9]+: cov:/ { for (i = 1; i < NF; i++) if ($i == "time:") t = $(i + 1) } END { gsub(/s/, "", t); print t }' "$d/fuzz.log")

  # Findings: every artifact libFuzzer saved, minimized, with its first failure line.
  nfind=0
  : > "$d/findings.txt"
  for a in "$d/art/"*; do
    [ -f "$a" ] || continue
    nfind=$((nfind + 1))
    name=$(basename "$a")
    env $(run_env "$t") timeout 600 "$bin" -minimize_crash=1 -runs=10000 -timeout="$(input_timeout "$t")" \
        -exact_artifact_path="$d/min/$name" "$a" > "$d/min/$name.log" 2>&1 || true
    [ -f "$d/min/$name" ] || cp "$a" "$d/min/$name"
    why=$(env $(run_env "$t") timeout 120 "$bin" "$d/min/$name" 2>&1 |
          grep -m1 -E 'FUZZ_CHECK failed|ERROR: (Address|Undefined|Leak)Sanitizer|runtime error|ALARM|out-of-memory|deadly signal' || true)
    echo "$d/min/$name: ${why:-does not fail when replayed alone}" >> "$d/findings.txt"
  done
  note=""
  [ "$rc" -eq 0 ] || note=" (exit $rc; see $d/fuzz.log)"
  echo "| $DATE | $COMMIT$DIRTY | $t | $MINUTES (${elapsed:-?} s) | $execs | $cov | $ft | $nfind$note |" >> "$SUMMARY"
done

echo
cat "$SUMMARY"
for t in $TARGETS; do
  f="$SCRATCH/$t/findings.txt"
  [ -s "$f" ] && { echo; echo "findings of $t:"; cat "$f"; }
done
echo
echo "Logs, scratch corpora and minimized findings: $SCRATCH/<target>/. Add coverage-adding"
echo "inputs by hand: tools/fuzz.sh merge <target> lists them; copy a handful into fuzz/corpus/<target>/."
