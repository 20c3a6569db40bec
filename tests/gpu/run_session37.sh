#!/bin/bash
# The thirty-seventh session's lease (headless .devrt with bin/strata.xz, strata_gpu_tests.xz and
# debs-x, whose libepoxy and GLFW the strata binary links):
# CUDA against the CPU after rays through an open mesh's holes are left empty (shared_math.h's
# normalizeLeafRay, both backends). Results in $OUT/r: gpu_tests.txt (with AnOpenMeshMatches),
# exports.txt (the bundled scenes and a bunny with holes, marked open in its scene, exported by
# both backends and compared byte for byte), open.txt (the open bunny's check on each backend).
# Copies strata and strata_gpu_gl_tests (when carried) to /tmp/devbin for run_session37_editor.sh.
source tests/gpu/devrt_start.sh
mkdir -p /tmp/devbin && cp $B/strata $B/strata_gpu_gl_tests /tmp/devbin/ 2>/dev/null
nvidia-smi -L > $R/host.txt 2>&1; nproc >> $R/host.txt
timeout 300 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt
tail -3 $R/gpu_tests.txt
exports_cpu_vs_cuda demo armadillo_bunny
# Every 400th triangle of the bunny left out: 9 holes, 27 open edges.
python3 - <<'P'
lines = open('tests/data/bunny.obj').read().split('\n')
out, faces = [], 0
for l in lines:
    if l.startswith('f '):
        faces += 1
        if faces % 400 == 0:
            continue
    out.append(l)
open('/tmp/holey_bunny.obj', 'w').write('\n'.join(out))
P
cat > $S/holey_bunny.strata.json <<'J'
{"format": "strata-scene", "version": 5, "unit": "mm", "settings": {"resolution": 512},
 "root": {"id": 1, "type": "union", "children": [
   {"id": 2, "type": "mesh", "path": "/tmp/holey_bunny.obj", "open": true}]}}
J
for b in cpu cuda; do
  echo "== holey bunny 512 $b" >> $R/open.txt
  timeout 120 $B/strata export $S/holey_bunny.strata.json --backend $b -o /tmp/open_$b.stl >> $R/open.txt 2>&1
done
cmp -s /tmp/open_cpu.stl /tmp/open_cuda.stl && echo "   CPU = CUDA, byte for byte" >> $R/open.txt || echo "   FILES DIFFER" >> $R/open.txt
grep -E "==|check|volume|specks|result|CPU|DIFFER" $R/open.txt
