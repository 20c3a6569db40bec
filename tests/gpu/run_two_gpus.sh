#!/bin/bash
# One lease on the two-GPU H200 host (issue #15): GPU tests (the export on several CUDA workers
# included), then exports with --gpus 1 and --gpus 2 of the rebuilt bone scaffold, the issue's
# scaffold and armadillo - bunny at 2048 and 4096 cells: wall time, stage times, tiles, host
# peak memory, each GPU's peak memory (nvidia-smi sampled every 100 ms), and the two outputs
# compared byte for byte. Carried in .devrt2 (no X runtime): bin/strata.xz,
# bin/strata_gpu_tests.xz. Results go to $OUT/r as they come (a lease may end early).
source tests/gpu/lease_start.sh
stages() { python3 -c "import json;d=json.load(open('/tmp/x.json'));print(' '.join('%s %.3f'%(s['name'],s['seconds']) for s in d['stages']), 'tiles', d['tiles'])"; }
source tests/gpu/gpu_memory.sh
run() {  # scene resolution gpus
  gpu_sampler_start
  /usr/bin/time -f "wall %e s, host peak %M KiB" timeout 280 $B/strata export $S/$1.strata.json --resolution $2 \
    --backend cuda --gpus $3 -q -o /tmp/x-$3.stl --report /tmp/x.json > /tmp/x.txt 2>&1
  local rc=$?
  gpu_sampler_stop
  echo "== $1 $2 --gpus $3: rc $rc $(tail -1 /tmp/x.txt) | $(stages 2>&1 | tail -1) | $(gpumax) | $(ls -l /tmp/x-$3.stl 2>/dev/null | awk '{print $5}') bytes"
  [ $rc = 0 ] || tail -5 /tmp/x.txt
}
for res in 2048 4096; do for scene in bone_scaffold bone_scaffold_scaled_copy armadillo_bunny; do
  for gpus in 1 2; do run $scene $res $gpus >> $R/two_gpus.txt 2>&1; done
  if cmp -s /tmp/x-1.stl /tmp/x-2.stl; then echo "   --gpus 1 = --gpus 2, byte for byte" >> $R/two_gpus.txt
  else echo "   outputs differ (or missing)" >> $R/two_gpus.txt; fi
  rm -f /tmp/x-1.stl /tmp/x-2.stl
done; done
cat $R/two_gpus.txt
