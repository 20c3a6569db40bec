#!/bin/bash
# The thirty-fifth session's fifth lease, second call (the packed X runtime alone): edit-to-screen
# at 512 and 1024 cells, interop and the host path, each frame's time split into building the
# panels, the view, the panels' drawing and the present (measure-latency's new parts), in
# $OUT/r/editor.txt.
[ -d /tmp/devbin ] || { echo "no /tmp/devbin: run run_session35d.sh first on this machine"; exit 1; }
DEVBIN=/tmp/devbin source tests/gpu/devrt_x_start.sh
latency_set strata > $R/editor.txt 2>&1
grep -E "^(==|latency)" $R/editor.txt | sed -E 's/ \(cuda.*//'
