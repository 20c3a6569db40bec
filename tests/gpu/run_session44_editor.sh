#!/bin/bash
# The forty-fourth session's lease, second call, the packed X runtime carried alone (the libraries
# and binaries from run_session44.sh in /tmp/devlib and /tmp/devbin): the editor's pixels through
# interop and the host path (gl_tests.txt), and edit-to-screen at 512 and 1024 cells through
# interop and the host path (editor.txt in $OUT/r), after the forty-third session's drafts kept
# after a drag and this session's editor changes.
[ -d /tmp/devbin ] || { echo "no /tmp/devbin: run run_session44.sh first on this machine"; exit 1; }
DEVBIN=/tmp/devbin source tests/gpu/devrt_x_start.sh
timeout 240 $B/strata_gpu_gl_tests > $R/gl_tests.txt 2>&1; echo "gl tests rc $?" >> $R/gl_tests.txt
tail -3 $R/gl_tests.txt
latency_set strata > $R/editor.txt 2>&1
grep -E "^(==|latency)" $R/editor.txt
