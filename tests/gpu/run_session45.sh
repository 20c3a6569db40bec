#!/bin/bash
# The forty-fifth session's lease, one headless call (carried: .devrt of make-runtime.sh,
# libs.tar.xz, bin/strata.xz, strata_gpu_tests.xz, strata_gpu_gl_tests.xz): the GPU tests, CPU
# against CUDA byte for byte on four bundled scenes, the editor's pixels through headless EGL (GL
# tests), the bone scaffold at 1024 cells on both backends, and the spread of the export's time
# estimate (each probe now the middle of up to three runs) over five runs a backend, beside the
# job's own wall time. Results in $OUT/r.
source tests/gpu/devrt_start.sh
first_call_checks
exports_cpu_vs_cuda demo armadillo_bunny bone_scaffold flange_patterns
timeout 240 $B/strata_gpu_gl_tests > $R/gl_tests.txt 2>&1; echo "gl tests rc $?" >> $R/gl_tests.txt
tail -3 $R/gl_tests.txt
for b in cuda cpu; do
  /usr/bin/time -f "wall %e s" timeout 120 $B/strata export $S/bone_scaffold.strata.json --resolution 1024 --backend $b -o /tmp/s.stl > $R/scaffold1024_$b.txt 2>&1
  grep -E "estimate|wall|^time" $R/scaffold1024_$b.txt | head -6
  for i in 1 2 3 4 5; do
    timeout 60 $B/strata export $S/demo.strata.json --resolution 1024 --backend $b -o /tmp/d.stl --max-memory 1K 2>&1 | grep -o "file, [0-9.]* [a-z]*" | head -1
  done > $R/estimates_demo1024_$b.txt
  /usr/bin/time -f "wall %e s" timeout 120 $B/strata export $S/demo.strata.json --resolution 1024 --backend $b -o /tmp/d.stl > $R/demo1024_$b.txt 2>&1
  echo "demo 1024 $b estimates: $(tr '\n' ';' < $R/estimates_demo1024_$b.txt) job: $(grep -E "^wall" $R/demo1024_$b.txt)"
done
rm -f /tmp/s.stl /tmp/d.stl
