#!/bin/bash
# One lease (thirty-fifth session), run from the project root on the device with the headless
# .devrt carried (make-runtime.sh; bin/*.xz: strata and strata_gpu_tests of this session).
# Results go to $OUT/r:
# - gpu_tests.txt: CUDA against the CPU (AGhostBeyondTheResultsGridMatchesTheCpu now takes the
#   ghosts the preview worker publishes after its result);
# - exports.txt: two bundled scenes exported by both backends at 512 cells, compared byte for
#   byte (the export path did not change: a guard).
source tests/gpu/devrt_start.sh
nvidia-smi -L > $R/host.txt 2>&1; nproc >> $R/host.txt
timeout 300 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt
tail -3 $R/gpu_tests.txt
for scene in demo armadillo_bunny; do
  for b in cpu cuda; do
    timeout 120 $B/strata export $S/$scene.strata.json --resolution 512 --backend $b -q -o /tmp/$b.stl > /tmp/$b.log 2>&1
    echo "== $scene 512 $b: rc $?" >> $R/exports.txt
  done
  cmp -s /tmp/cpu.stl /tmp/cuda.stl && echo "   CPU = CUDA, byte for byte" >> $R/exports.txt || echo "   FILES DIFFER" >> $R/exports.txt
  rm -f /tmp/cpu.stl /tmp/cuda.stl
done
cat $R/exports.txt
