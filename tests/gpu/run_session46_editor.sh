#!/bin/bash
# The forty-sixth session's lease, second call, the packed X runtime carried alone (the libraries
# and binaries from run_session46.sh in /tmp/devlib and /tmp/devbin): the editor's pixels through
# interop and the host path in a real window (gl_tests.txt: they skipped in the forty-fifth
# session's headless call), and edit-to-screen at 512 and 1024 cells through interop and the host
# path (editor.txt in $OUT/r), after this session's viewport changes (the view kept whole as it
# changes shape, the labels off the gizmo, the settled-edit check).
[ -d /tmp/devbin ] || { echo "no /tmp/devbin: run run_session46.sh first on this machine"; exit 1; }
DEVBIN=/tmp/devbin source tests/gpu/devrt_x_start.sh
# Xvfb may not take connections yet (the first try of this call failed to open :99, while the
# latency runs after it opened their windows): wait for its socket, then a moment.
for i in $(seq 50); do [ -e /tmp/.X11-unix/X99 ] && break; sleep 0.2; done; sleep 1
timeout 240 $B/strata_gpu_gl_tests > $R/gl_tests.txt 2>&1; echo "gl tests rc $?" >> $R/gl_tests.txt
tail -3 $R/gl_tests.txt
[ "$1" = gl ] && exit 0  # the GL tests alone
latency_set strata > $R/editor.txt 2>&1
grep -E "^(==|latency)" $R/editor.txt
