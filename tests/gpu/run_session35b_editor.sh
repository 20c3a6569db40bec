#!/bin/bash
# The thirty-fifth session's second lease, second call, the packed X runtime carried alone (the
# libraries and binaries from run_session35b.sh in /tmp/devlib and /tmp/devbin). Results go to
# $OUT/r:
# - gl_tests.txt: the editor's pixels through interop, the host path and the CPU backend (the
#   renderer now keeps the image of the splats alone and draws ghosts and lines over it);
# - ghost_*.png: the plate with cutters sticking out, ghosts shown, through both paths;
# - editor.txt: edit-to-screen at 512 and 1024 cells, interop and the host path (the final build).
[ -d /tmp/devbin ] || { echo "no /tmp/devbin: run run_session35b.sh first on this machine"; exit 1; }
DEVBIN=/tmp/devbin source tests/gpu/devrt_x_start.sh
timeout 240 $B/strata_gpu_gl_tests > $R/gl_tests.txt 2>&1; echo "gl tests rc $?" >> $R/gl_tests.txt
tail -3 $R/gl_tests.txt
ghost_shots
{
latency_set strata
latency strata /tmp/rod.strata.json "long pin" 512 --ghosts
} > $R/editor.txt 2>&1
grep -E "^(==|latency)" $R/editor.txt
