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
exports_cpu_vs_cuda demo armadillo_bunny
