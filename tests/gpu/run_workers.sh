#!/bin/bash
# One lease without the X runtime (eleventh session, issues #15 and #13): GPU tests (the export
# on several CUDA workers included), exports with --gpus 1, 2 and 3 on the lent GPU (several
# workers share it: one's host-side contouring overlaps another's device work), compared byte
# for byte, and the CPU backend's export on the host's cores (bit-plane node sides). Carried in
# .devrt2 as run_host_stages.sh says.
source .devrt2/on-device.sh
for f in .devrt2/bin/strata.xz .devrt2/bin/strata_gpu_tests.xz; do xz -dkf "$f"; done
chmod +x .devrt2/bin/strata .devrt2/bin/strata_gpu_tests
B=.devrt2/bin; S=assets/scenes; R=$OUT/r; mkdir -p $R
export STRATA_ASSETS=$PWD/assets STRATA_TEST_DATA=$PWD/tests/data
nvidia-smi -L > $R/gpus.txt 2>&1
timeout 300 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt
stages() { python3 -c "import json;d=json.load(open('/tmp/x.json'));print(' '.join('%s %.3f'%(s['name'],s['seconds']) for s in d['stages']))"; }
{
for res in 1024 2048; do for scene in bone_scaffold_scaled_copy armadillo_bunny bone_scaffold; do
  for gpus in 1 2 3; do for rep in 1 2; do
    /usr/bin/time -f "wall %e s, peak %M KiB" $B/strata export $S/$scene.strata.json --resolution $res \
      --backend cuda --gpus $gpus -q -o /tmp/x-$gpus.stl --report /tmp/x.json > /tmp/x.txt 2>&1
    echo "== $scene $res --gpus $gpus (run $rep): $(tail -1 /tmp/x.txt) $(stages) tiles $(python3 -c "import json;print(json.load(open('/tmp/x.json'))['tiles'])")"
  done; done
  cmp -s /tmp/x-1.stl /tmp/x-2.stl && cmp -s /tmp/x-1.stl /tmp/x-3.stl && echo "   --gpus 1 = 2 = 3, byte for byte"
done; done
for res in 1024 2048; do
  /usr/bin/time -f "wall %e s, peak %M KiB" $B/strata export $S/armadillo_bunny.strata.json --resolution $res \
    --backend cpu -q -o /tmp/c.stl --report /tmp/x.json > /tmp/x.txt 2>&1
  echo "== armadillo_bunny $res cpu 16 cores: $(tail -1 /tmp/x.txt) $(stages)"
done
} > $R/workers.txt 2>&1
tar czf $OUT/results.tgz -C $OUT r
