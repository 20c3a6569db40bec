#!/bin/bash
# The forty-sixth session's lease, first call, headless (carried: .devrt of make-runtime.sh,
# libs.tar.xz, bin/strata.xz, strata_gpu_tests.xz, strata_gpu_gl_tests.xz): the GPU tests, CPU
# against CUDA byte for byte on four bundled scenes, and the bone scaffold at 1024 cells on both
# backends (stage times, wall). Keeps the binaries in /tmp/devbin for the second call
# (run_session46_editor.sh). Results in $OUT/r.
source tests/gpu/devrt_start.sh
first_call_checks
exports_cpu_vs_cuda demo armadillo_bunny bone_scaffold flange_patterns
for b in cuda cpu; do
  /usr/bin/time -f "wall %e s" timeout 120 $B/strata export $S/bone_scaffold.strata.json --resolution 1024 --backend $b -o /tmp/s.stl > $R/scaffold1024_$b.txt 2>&1
  grep -E "wall|^time" $R/scaffold1024_$b.txt | head -4
done
rm -f /tmp/s.stl
