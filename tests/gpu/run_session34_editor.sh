#!/bin/bash
# The thirty-fourth session's second call on the same warm machine, the X runtime carried
# (make-runtime.sh --x11 --pack) with bin/strata.xz only: the libraries the host lacks are those
# the first call (run_session34.sh) unpacked into /tmp/devlib (the carried tree would not hold
# both). Results go to $OUT/r:
# - ghost_interop.png, ghost_host.png: the editor on CUDA (through interop, and the host path)
#   with a plate whose two cutters stick out of it on every side, ghosts shown: drawn whole;
# - editor.txt: edit-to-screen (#11: --measure-latency 12, the demo and armadillo - bunny at 512
#   and 1024 cells, interop and the host path, splats as the renderer picks).
source tests/gpu/devrt_x_start.sh
ghost_shots
latency_set strata > $R/editor.txt 2>&1
grep -E "^(==|latency)" $R/editor.txt
