#!/bin/bash
# One lease (one GPU; issue #15): GPU tests (the device's crop against the CPU's, a tiled export
# of the rebuilt scaffold against the CPU and one tile), then `strata export` of the rebuilt
# bone scaffold (offsets, shells, roundings: tiled with the modifiers' halo) at 1024, 2048 and
# 4096 cells on CUDA with the estimate printed first: wall, stages, tiles, host and GPU peak
# memory; at 2048 also in tiles of 256 cells, compared byte for byte; and armadillo - bunny at
# 4096 (the estimate against what the export took). Carried in .devrt2 (no X runtime):
# bin/strata.xz, bin/strata_gpu_tests.xz. Results go to $OUT/r as they come.
source tests/gpu/lease_start.sh
stages() { python3 -c "import json;d=json.load(open('/tmp/x.json'));print(' '.join('%s %.3f'%(s['name'],s['seconds']) for s in d['stages']), 'tiles', d['tiles'], 'triangles', d['check']['triangles'], 'passed', d['check']['passed'])"; }
gpumax() { python3 -c "
m=0
for l in open('/tmp/mem.txt'):
  p=l.strip()
  if p.isdigit(): m=max(m,int(p))
print('GPU peak MiB', m)"; }
run() {  # scene resolution label [extra options]
  local scene=$1 res=$2 label=$3; shift 3
  nvidia-smi --query-gpu=memory.used --format=csv,noheader,nounits -lms 100 > /tmp/mem.txt 2>/dev/null &
  local sampler=$!
  /usr/bin/time -f "wall %e s, host peak %M KiB" timeout 290 $B/strata export $S/$scene.strata.json \
    --resolution $res --backend cuda -q -o /tmp/x-$label.stl --report /tmp/x.json \
    --max-memory 1K --force "$@" > /tmp/x.txt 2>&1
  local rc=$?
  kill $sampler 2>/dev/null; wait $sampler 2>/dev/null
  echo "== $scene $res $label $*: rc $rc | $(grep -o 'estimate for.*' /tmp/x.txt | sed 's/ -- needs.*//' | cut -c1-220)"
  echo "   $(tail -1 /tmp/x.txt) | $(stages 2>&1 | tail -1) | $(gpumax) | $(ls -l /tmp/x-$label.stl 2>/dev/null | awk '{print $5}') bytes"
  [ $rc = 0 ] || tail -5 /tmp/x.txt
}
run bone_scaffold 1024 a >> $R/tiles.txt 2>&1
run bone_scaffold 2048 auto >> $R/tiles.txt 2>&1
run bone_scaffold 2048 t256 --tile 256 >> $R/tiles.txt 2>&1
if cmp -s /tmp/x-auto.stl /tmp/x-t256.stl; then echo "   2048: auto tiles = tiles of 256, byte for byte" >> $R/tiles.txt
else echo "   2048: outputs differ (or missing)" >> $R/tiles.txt; fi
rm -f /tmp/x-*.stl
cat $R/tiles.txt
run armadillo_bunny 4096 ab >> $R/tiles.txt 2>&1; rm -f /tmp/x-*.stl
run bone_scaffold 4096 b >> $R/tiles.txt 2>&1; rm -f /tmp/x-*.stl
tail -4 $R/tiles.txt
