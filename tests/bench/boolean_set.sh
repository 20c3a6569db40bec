#!/usr/bin/env bash
# The boolean set of the export-speed issue: 21 cases (union, intersection and difference of 7
# pairs of real meshes from ../shared/data and analytic ones from make_boolean_set.py), each
# `strata boolean OP A B --resolution R -o case.stl` on one backend, timed as a user meets it
# (wall time of the command), with each case's JSON report and file kept in OUTDIR.
#   usage: boolean_set.sh STRATA DATA ANALYTIC OUTDIR BACKEND [RESOLUTION]
# DATA holds armadillo, bunny, blobby, eight, elephant, fandisk, knot1 (.obj); ANALYTIC the
# sphere, box and torus. Prints one line per case (case, wall seconds, exit code) and the total.
# With BATCH=1: the 21 commands written to OUTDIR/jobs.txt and run as one `strata batch` (one
# process, the backend started once); prints the batch's wall time and exit code.
set -u
strata=$1 data=$2 analytic=$3 out=$4 backend=$5 resolution=${6:-512}
mkdir -p "$out"
pairs="fandisk:knot1 elephant:blobby eight:knot1 armadillo:bunny fandisk:@sphere knot1:@box @sphere:@torus"
mesh() { case $1 in @*) echo "$analytic/${1#@}.obj" ;; *) echo "$data/$1.obj" ;; esac; }
if [ "${BATCH:-0}" = 1 ]; then
  : > "$out/jobs.txt"
  for pair in $pairs; do
    a=${pair%%:*} b=${pair##*:}
    for op in union intersection difference; do
      name="${op}_${a#@}_${b#@}"
      printf "boolean %s '%s' '%s' --resolution %s --backend %s -q -o '%s' --report '%s'\n" \
        $op "$(mesh "$a")" "$(mesh "$b")" "$resolution" "$backend" "$out/$name.stl" \
        "$out/$name.json" >> "$out/jobs.txt"
    done
  done
  start=$(date +%s.%N)
  "$strata" batch "$out/jobs.txt" -q > "$out/batch.txt" 2>&1
  rc=$?
  end=$(date +%s.%N)
  printf "%-36s %8.3f s  rc %d\n" "batch ($backend, $resolution cells)" \
    "$(awk "BEGIN { print $end - $start }")" "$rc"
  exit 0
fi
total=0
for pair in $pairs; do
  a=${pair%%:*} b=${pair##*:}
  for op in union intersection difference; do
    name="${op}_${a#@}_${b#@}"
    start=$(date +%s.%N)
    "$strata" boolean $op "$(mesh "$a")" "$(mesh "$b")" --resolution "$resolution" \
      --backend "$backend" -q -o "$out/$name.stl" --report "$out/$name.json" > "$out/$name.txt" 2>&1
    rc=$?
    end=$(date +%s.%N)
    wall=$(awk "BEGIN { print $end - $start }")
    total=$(awk "BEGIN { print $total + $wall }")
    printf "%-36s %8.3f s  rc %d\n" "$name" "$wall" "$rc"
  done
done
printf "%-36s %8.3f s\n" "total ($backend, $resolution cells)" "$total"
