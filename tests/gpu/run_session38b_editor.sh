#!/bin/bash
# The thirty-eighth session's second lease, second call, the packed X runtime carried alone (the
# libraries and binaries from run_session38b.sh in /tmp/devlib and /tmp/devbin): the editor's
# pixels (gl_tests.txt) and edit-to-screen at 512 and 1024 cells through interop and the host
# path, moves one at a time and as one drag (a drag's draft now finishes before the newest
# position is taken: editor.txt in $OUT/r).
[ -d /tmp/devbin ] || { echo "no /tmp/devbin: run run_session38b.sh first on this machine"; exit 1; }
DEVBIN=/tmp/devbin source tests/gpu/devrt_x_start.sh
timeout 240 $B/strata_gpu_gl_tests > $R/gl_tests.txt 2>&1; echo "gl tests rc $?" >> $R/gl_tests.txt
tail -3 $R/gl_tests.txt
{
latency_set strata
for res in 512 1024; do
  echo "== drag strata armadillo_bunny 'bunny' $res"
  timeout 120 $B/strata edit $S/armadillo_bunny.strata.json --measure-latency 12 --move-leaf bunny \
    --drag --resolution $res --backend cuda --splats auto 2>&1 | grep -E "^(drag:|strata)"
done
} > $R/editor.txt 2>&1
grep -E "^(==|latency|drag:)" $R/editor.txt
