#!/bin/bash
# The forty-second session's lease (headless .devrt with bin/strata.xz, strata_gpu_tests.xz and
# data/setmeshes.tar.xz): CUDA against the CPU after the evaluator's new warnings (a turned thin
# part, a part far from the rest), then the boolean set (tests/bench/boolean_set.sh, 21 cases at
# 512 cells) as one `strata batch` on each backend, two rounds, with the stage sums and merge
# steps of the reports; then how much of the write is the disk: the set's files, rewritten from
# memory by the same process with and without an fsync each (set_write.py). Results in $OUT/r.
source tests/gpu/devrt_start.sh
first_call_checks
exports_cpu_vs_cuda demo armadillo_bunny bone_scaffold
tar xJf .devrt/data/setmeshes.tar.xz -C /tmp; M=/tmp/meshes; A=/tmp/analytic
{
for round in 1 2; do
  for bk in cuda cpu; do
    rm -rf /tmp/set-$bk
    BATCH=1 bash tests/bench/boolean_set.sh $B/strata $M $A /tmp/set-$bk $bk 512
    python3 tests/gpu/set_stage_sums.py /tmp/set-$bk
  done
done
differ=0
for f in /tmp/set-cuda/*.stl; do cmp -s $f /tmp/set-cpu/$(basename $f) || differ=$((differ+1)); done
echo "cuda against cpu: $differ of $(ls /tmp/set-cuda/*.stl | wc -l) files differ"
python3 tests/gpu/set_write.py /tmp/set-cuda
df -h /tmp | tail -1
} > $R/set.txt 2>&1
cat $R/set.txt
