#!/bin/bash
# The forty-fourth session's lease, one headless call (carried: .devrt of make-runtime.sh,
# libs.tar.xz, bin/strata.xz, strata_gpu_tests.xz, strata_gpu_gl_tests.xz): the GPU tests, CPU
# against CUDA byte for byte on four bundled scenes after this session's changes (the estimate's
# probe counts its bodies), an export at 1024 cells whose bodies the probe saw otherwise (the
# warning on the device), and the editor's pixels through headless EGL (GL tests). Results in
# $OUT/r.
source tests/gpu/devrt_start.sh
first_call_checks
exports_cpu_vs_cuda demo armadillo_bunny bone_scaffold flange_patterns
timeout 240 $B/strata_gpu_gl_tests > $R/gl_tests.txt 2>&1; echo "gl tests rc $?" >> $R/gl_tests.txt
tail -3 $R/gl_tests.txt
for b in cuda cpu; do
  /usr/bin/time -f "wall %e s" timeout 120 $B/strata export $S/bone_scaffold.strata.json --resolution 1024 --backend $b -q -o /tmp/s.stl > $R/scaffold1024_$b.txt 2>&1
  grep -E "bodies|components|wall|stages|evaluate|contour|merge|write|check" $R/scaffold1024_$b.txt | head -12
done
