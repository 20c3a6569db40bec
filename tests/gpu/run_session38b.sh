#!/bin/bash
# The thirty-eighth session's second lease, first call (headless .devrt with bin/strata.xz,
# strata_gpu_tests.xz, strata_gpu_gl_tests.xz and debs-x): CUDA against the CPU after an open
# mesh's triangles count as resolved for the speck rule (contour_scene.cpp) and modifiers may be
# applied by coarse drafts; the bundled scenes and a bracket beside a cube without its top face,
# marked open, exported by both backends and compared byte for byte (exports.txt, open.txt).
# Copies the binaries to /tmp/devbin for run_session38b_editor.sh.
source tests/gpu/devrt_start.sh
mkdir -p /tmp/devbin && cp $B/strata $B/strata_gpu_gl_tests /tmp/devbin/ 2>/dev/null
nvidia-smi -L > $R/host.txt 2>&1; nproc >> $R/host.txt
timeout 300 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt
tail -3 $R/gpu_tests.txt
exports_cpu_vs_cuda demo armadillo_bunny bone_scaffold
python3 - <<'P'
v = [(x, y, z) for z in (-5, 5) for y in (-5, 5) for x in (-5, 5)]
f = [(0, 2, 1), (1, 2, 3), (0, 1, 5), (0, 5, 4), (2, 6, 7), (2, 7, 3), (0, 4, 6), (0, 6, 2),
     (1, 3, 7), (1, 7, 5)]  # the top (z = +5) left out
with open('/tmp/cube_open.obj', 'w') as out:
    out.writelines('v %g %g %g\n' % p for p in v)
    out.writelines('f %d %d %d\n' % (a + 1, b + 1, c + 1) for a, b, c in f)
P
cat > $S/open_beside.strata.json <<'J'
{"format": "strata-scene", "version": 5, "unit": "mm", "settings": {"resolution": 512},
 "root": {"id": 1, "type": "union", "children": [
   {"id": 2, "type": "box", "size": [30, 20, 10]},
   {"id": 3, "type": "mesh", "path": "/tmp/cube_open.obj", "open": true,
    "transform": {"translate": [40, 0, 0]}}]}}
J
for b in cpu cuda; do
  echo "== open cube beside a box 512 $b" >> $R/open.txt
  timeout 120 $B/strata export $S/open_beside.strata.json --backend $b -o /tmp/open_$b.stl >> $R/open.txt 2>&1
done
cmp -s /tmp/open_cpu.stl /tmp/open_cuda.stl && echo "   CPU = CUDA, byte for byte" >> $R/open.txt || echo "   FILES DIFFER" >> $R/open.txt
grep -E "==|check |components|specks|result|CPU|DIFFER" $R/open.txt
