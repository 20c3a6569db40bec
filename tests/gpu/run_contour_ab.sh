#!/bin/bash
# One lease without the X runtime (twenty-first session, issue #13): after the CPU contour's
# rework (polygons counted first and written in place, boundary rows indexed, uninitialised
# growth) and the device contour's in-place face download: the GPU tests (CUDA against the CPU),
# the benchmark, and export stage times of both scaffolds and armadillo - bunny on both backends
# with the files compared byte for byte. Carried: .devrt/{on-device.sh,debs-gl,libs.tar.xz,bin}
# (bin: strata, strata_gpu_tests, strata_gpu_bench, stripped and xz'd).
source .devrt/on-device.sh
mkdir -p /tmp/devlib && tar xJf .devrt/libs.tar.xz -C /tmp/devlib
export LD_LIBRARY_PATH=/tmp/devlib:$LD_LIBRARY_PATH
for f in .devrt/bin/*.xz; do xz -dkf "$f"; done
B=.devrt/bin; chmod +x $B/strata $B/strata_gpu_tests $B/strata_gpu_bench
S=assets/scenes; R=$OUT/r; mkdir -p $R
export STRATA_ASSETS=$PWD/assets STRATA_TEST_DATA=$PWD/tests/data
nvidia-smi --query-gpu=name --format=csv,noheader > $R/device.txt 2>&1
timeout 240 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt
timeout 150 $B/strata_gpu_bench --resolutions 512,1024,2048 --cpu-max 512 --offset-cpu-max 0 \
  --assets assets --data assets/meshes > $R/bench.txt 2>&1; echo "bench rc $?" >> $R/bench.txt
{
for res in 512 1024 2048; do for scene in bone_scaffold_scaled_copy armadillo_bunny; do for bk in cuda cpu; do
  [ $bk = cpu ] && [ $res = 2048 ] && continue
  /usr/bin/time -f "wall %e s, peak %M KiB" $B/strata export $S/$scene.strata.json --resolution $res \
    --backend $bk -q -o /tmp/x-$bk.stl --report /tmp/x.json > /tmp/x.txt 2>&1
  echo "== export $scene $res $bk: $(tail -1 /tmp/x.txt) $(python3 -c "import json;d=json.load(open('/tmp/x.json'));print(' '.join('%s %.3f'%(s['name'],s['seconds']) for s in d['stages']))")"
  done; [ $res != 2048 ] && { cmp -s /tmp/x-cuda.stl /tmp/x-cpu.stl && echo "   cuda = cpu, byte for byte" || echo "   cuda != cpu"; }
done; done
} > $R/export.txt 2>&1
