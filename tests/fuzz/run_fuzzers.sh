#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, tests/fuzz/README.md) and runs each for SECONDS over its
# corpus, seeded from tests/fuzz/seeds and assets/scenes. Prints the executions per target and
# fails on any finding (a crash, sanitizer report, leak, -timeout hang or -rss_limit_mb
# overrun); the input is then in $FUZZ_DIR/findings/<target>/.
#
# Usage: tests/fuzz/run_fuzzers.sh SECONDS [TARGET...]
#   SECONDS   per target (CI: 60; by hand: hours, e.g. 14400)
#   TARGET    fuzz_mesh_readers fuzz_scene_file fuzz_pipeline fuzz_expansion (default: all)
# Environment: FUZZ_DIR (default build-fuzz) holds the build, the growing corpora and findings;
# JOBS (default nproc) build jobs.
# -timeout=60: the instrumented engine runs 100-250x slower than a Release build (coverage
# callbacks on every compare), and libFuzzer runs an input twice when it suspects a leak; a
# 48-tile export of a smooth torus (seeds/pipeline_slow/many_tiles_smooth_torus, 0.1 s in
# Release) took 25 s here. Such findings stay out of the corpus (a minute's run of
# fuzz_pipeline made 15 executions with it); FuzzCorpus runs them in every build. A hang runs forever, so it is still caught.
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${1:?usage: tests/fuzz/run_fuzzers.sh SECONDS [TARGET...]}
shift
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(fuzz_mesh_readers fuzz_scene_file fuzz_pipeline fuzz_expansion)
dir=${FUZZ_DIR:-build-fuzz}
jobs=${JOBS:-$(nproc)}

CC=clang CXX=clang++ cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSTRATA_FUZZ=ON \
  -DSTRATA_EDITOR=OFF >/dev/null
cmake --build "$dir" -j"$jobs" --target "${targets[@]}"

failed=0
printf '\n%-20s %12s %10s %8s  %s\n' target executions exec/s edges result
for t in "${targets[@]}"; do
  corpus="$dir/corpus/$t"
  findings="$dir/findings/$t"
  mkdir -p "$corpus" "$findings"
  case $t in
    fuzz_mesh_readers) cp -n tests/fuzz/seeds/mesh_readers/* "$corpus/" ;;
    fuzz_scene_file) cp -n assets/scenes/*.strata.json "$corpus/" ;;
    fuzz_pipeline) cp -n tests/fuzz/seeds/pipeline/* "$corpus/" ;;
  esac
  log="$dir/$t.log"
  set +e
  "$dir/tests/fuzz/$t" -max_total_time="$seconds" -timeout=60 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$findings/" "$corpus" >"$log" 2>&1
  rc=$?
  set -e
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  speed=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  edges=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  if [ $rc -eq 0 ]; then
    result=ok
  else
    result="FOUND (exit $rc): $(ls "$findings" | head -3 | tr '\n' ' ')"
    failed=1
  fi
  printf '%-20s %12s %10s %8s  %s\n' "$t" "${runs:-?}" "${speed:-?}" "${edges:-?}" "$result"
  if [ $rc -ne 0 ]; then
    echo "---- last lines of $log"
    tail -40 "$log"
  fi
done
exit $failed
