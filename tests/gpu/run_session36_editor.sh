#!/bin/bash
# The thirty-sixth session's lease, second call, the packed X runtime carried alone (the libraries
# and binaries from run_session36.sh in /tmp/devlib and /tmp/devbin). Results in $OUT/r:
# - gl_tests.txt: the editor's pixels through interop, the host path and the CPU backend;
# - ghost_*.png: the plate with cutters sticking out, ghosts shown (each ghost now drawn with its
#   own lattice's splats), through both paths;
# - editor.txt: edit-to-screen at 512 and 1024 cells, interop and the host path (the view's clip
#   planes now follow the scene by quarter powers of two).
[ -d /tmp/devbin ] || { echo "no /tmp/devbin: run run_session36.sh first on this machine"; exit 1; }
DEVBIN=/tmp/devbin source tests/gpu/devrt_x_start.sh
timeout 240 $B/strata_gpu_gl_tests > $R/gl_tests.txt 2>&1; echo "gl tests rc $?" >> $R/gl_tests.txt
tail -3 $R/gl_tests.txt
ghost_shots
{
latency_set strata
latency strata /tmp/rod.strata.json "long pin" 512 --ghosts
} > $R/editor.txt 2>&1
grep -E "^(==|latency)" $R/editor.txt
