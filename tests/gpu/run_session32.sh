#!/bin/bash
# One lease (thirty-second session, issue #15), run from the project root on the device with
# .devrt carried (make-runtime.sh without --x11; libs.tar.xz: the libraries the host lacks;
# bin/*.xz: strata and strata_gpu_tests of this session). Results go to $OUT/r:
# - gpu_tests.txt: CUDA against the CPU;
# - ply.txt: the rebuilt scaffold and armadillo - bunny at 4096 cells on one GPU, written in
#   pieces as binary STL and as PLY, and in memory as PLY: stages, wall, host peak, file size;
#   the streamed PLY compared byte for byte with the in-memory one.
source tests/gpu/devrt_start.sh
nvidia-smi -L > $R/host.txt 2>&1; nproc >> $R/host.txt; free -g >> $R/host.txt; df -h /tmp >> $R/host.txt
timeout 200 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt
tail -3 $R/gpu_tests.txt
stages() { python3 -c "import json;d=json.load(open('$1'));print(d['tiles'], 'tiles', ' '.join('%s %.3f'%(s['name'],s['seconds']) for s in d['stages']), 'triangles', d['check']['triangles'], 'vertices', d['check'].get('vertices'), 'passed', d['check']['passed'])"; }
run() {  # name, output, flags
  /usr/bin/time -f "wall %e s peak %M KiB" -o /tmp/t.txt timeout 250 $B/strata export $S/$scene.strata.json \
    --resolution 4096 --backend cuda -q -o $2 --report /tmp/r.json $3 > /tmp/x.log 2>&1
  echo "== $scene $1: rc $? $(tail -1 /tmp/t.txt) | $(stat -c %s $2 2>/dev/null) bytes | $(stages /tmp/r.json 2>&1 | tail -1)" >> $R/ply.txt
  tail -2 /tmp/x.log >> $R/ply.txt
}
for scene in armadillo_bunny bone_scaffold; do
  run "stream stl" /tmp/s.stl --stream; rm -f /tmp/s.stl
  run "stream ply" /tmp/s.ply --stream
  run "memory ply" /tmp/m.ply ""
  cmp -s /tmp/s.ply /tmp/m.ply && echo "   streamed PLY = in-memory PLY, byte for byte" >> $R/ply.txt || echo "   PLY DIFFER" >> $R/ply.txt
  rm -f /tmp/s.ply /tmp/m.ply
done
cat $R/ply.txt
