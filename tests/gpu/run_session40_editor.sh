#!/bin/bash
# The fortieth session's lease, second call, the packed X runtime carried alone (the libraries
# and binaries from run_session40.sh in /tmp/devlib and /tmp/devbin): the editor's pixels
# (gl_tests.txt), the plate's ghosts through interop and the host path, a part whose cutter is
# forty times its size with its ghost at 1024 cells (ghost_big.txt, .png: its window now at most
# 512 cells), and edit-to-screen at 512 and 1024 cells through interop and the host path
# (editor.txt in $OUT/r).
[ -d /tmp/devbin ] || { echo "no /tmp/devbin: run run_session40.sh first on this machine"; exit 1; }
DEVBIN=/tmp/devbin source tests/gpu/devrt_x_start.sh
timeout 240 $B/strata_gpu_gl_tests > $R/gl_tests.txt 2>&1; echo "gl tests rc $?" >> $R/gl_tests.txt
tail -3 $R/gl_tests.txt
ghost_shots
cat > /tmp/bigcut.strata.json <<'SCENE'
{"format":"strata-scene","version":1,"unit":"millimetre","settings":{"resolution":1024,"margin":0.05},
 "root":{"id":1,"name":"plate cut by a far box","type":"difference","children":[
  {"id":2,"name":"plate","type":"box","size":[2,2,2]},
  {"id":3,"name":"far box","type":"box","size":[40,40,40],"transform":{"translate":[0,0,20]}}]}}
SCENE
for run in 1 2; do
  start=$(date +%s.%N)
  timeout 120 $B/strata edit /tmp/bigcut.strata.json --select "far box" --backend cuda \
    --width 1280 --height 800 --screenshot $R/ghost_big.png >> $R/ghost_big.txt 2>&1
  echo "run $run rc $? wall $(awk "BEGIN { print $(date +%s.%N) - $start }") s" >> $R/ghost_big.txt
done
grep -E "^run|ghost" $R/ghost_big.txt | tail -6
latency_set strata > $R/editor.txt 2>&1
grep -E "^(==|latency)" $R/editor.txt
