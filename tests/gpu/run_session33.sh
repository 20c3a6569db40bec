#!/bin/bash
# One lease (thirty-third session), run from the project root on the device with .devrt carried
# (bin/*.xz: strata and strata_gpu_tests of this session). Results go to $OUT/r:
# - gpu_tests.txt: CUDA against the CPU (the offsets' surfels through a node now kept just past
#   it: engine/ldi/offset_math.h, shared by both backends);
# - modifiers.txt: an L of two boxes filleted and rounded, at resolutions where its faces lie on
#   planes of nodes (128, 192) and where they do not (96, 256), and the bundled bone scaffold
#   (true offsets) at 512 and 1024: exported by both backends, compared byte for byte, with the
#   sign disagreements and synthesized crossings each report counts (0 expected).
source tests/gpu/devrt_start.sh
nvidia-smi -L > $R/host.txt 2>&1; nproc >> $R/host.txt
timeout 300 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt
tail -3 $R/gpu_tests.txt
L='{"id":2,"type":"box","size":[2,1,1],"transform":{"translate":[1,0.5,0.5]}},{"id":3,"type":"box","size":[1,2,1],"transform":{"translate":[0.5,1,0.5]}}'
for kind in fillet round; do
  echo "{\"format\":\"strata-scene\",\"version\":4,\"root\":{\"id\":1,\"type\":\"$kind\",\"radius\":0.3,\"children\":[$L]}}" > /tmp/L_$kind.strata.json
done
report() { python3 -c "import json;d=json.load(open('$1'));print('volume %.6f'%d['volume'], 'disagreements', d['sign_disagreements'], 'synthesized', d['synthesized_crossings'], 'triangles', d['check']['triangles'], ' '.join('%s %.3f'%(s['name'],s['seconds']) for s in d['stages']))"; }
both() {  # scene file, resolution
  for b in cpu cuda; do
    timeout 250 $B/strata export $1 --resolution $2 --backend $b -q -o /tmp/$b.stl --report /tmp/$b.json > /tmp/$b.log 2>&1
    echo "== $(basename $1) $2 $b: rc $? | $(report /tmp/$b.json 2>&1 | tail -1)" >> $R/modifiers.txt
  done
  cmp -s /tmp/cpu.stl /tmp/cuda.stl && echo "   CPU = CUDA, byte for byte" >> $R/modifiers.txt || echo "   FILES DIFFER" >> $R/modifiers.txt
  rm -f /tmp/cpu.stl /tmp/cuda.stl
}
for kind in fillet round; do for res in 96 128 192 256 512; do both /tmp/L_$kind.strata.json $res; done; done
for res in 512 1024; do both $S/bone_scaffold.strata.json $res; done
cat $R/modifiers.txt
