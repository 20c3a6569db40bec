#!/bin/bash
# The thirty-eighth session's lease (headless .devrt with bin/strata.xz, strata_gpu_tests.xz,
# debs-x, and data/setmeshes.tar.xz: ../shared/data's meshes and the analytic ones of
# tests/bench/make_boolean_set.py): CUDA against the CPU after the meshes' bounds went through
# a tree of their vertices (engine/geometry/mesh_world_bounds.h) and modifiers weigh more in the
# evaluation's progress; then the boolean set (tests/bench/boolean_set.sh, 21 cases at 512
# cells) one command a case and as one `strata batch`, on each backend, alternating, every file
# compared with the first run's. Results in $OUT/r: gpu_tests.txt, exports.txt, set.txt.
source tests/gpu/devrt_start.sh
nvidia-smi -L > $R/host.txt 2>&1; nproc >> $R/host.txt
timeout 300 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt
tail -3 $R/gpu_tests.txt
exports_cpu_vs_cuda demo armadillo_bunny bone_scaffold
tar xJf .devrt/data/setmeshes.tar.xz -C /tmp; M=/tmp/meshes; A=/tmp/analytic
{
for round in 1 2; do
  for bk in cuda cpu; do
    bash tests/bench/boolean_set.sh $B/strata $M $A /tmp/set-one-$bk $bk 512 | tail -1
    BATCH=1 bash tests/bench/boolean_set.sh $B/strata $M $A /tmp/set-batch-$bk $bk 512
  done
done
same=0; differ=0
for f in /tmp/set-one-cuda/*.stl; do
  n=$(basename $f)
  for other in /tmp/set-batch-cuda /tmp/set-one-cpu /tmp/set-batch-cpu; do
    if cmp -s $f $other/$n; then same=$((same+1)); else differ=$((differ+1)); echo "   DIFFER: $other/$n"; fi
  done
done
echo "files: $same equal to the one-command cuda run's, $differ differ"
grep -h "rc [1-9]" /tmp/set-*/*.txt | head
tail -2 /tmp/set-batch-cuda/batch.txt
} > $R/set.txt 2>&1
cat $R/set.txt
