#!/bin/bash
# The fortieth session's lease, first call (headless .devrt with bin/strata.xz,
# strata_gpu_tests.xz, strata_gpu_gl_tests.xz, libs.tar.xz and debs-x): CUDA against the CPU after
# the preview's settling pass (a result at rest on the scene's own lattice) and ghosts' windows
# of at most 512 cells; the bundled scenes exported by both backends and compared byte for byte
# (exports.txt). Copies the binaries to /tmp/devbin for run_session40_editor.sh.
source tests/gpu/devrt_start.sh
mkdir -p /tmp/devbin && cp $B/strata $B/strata_gpu_gl_tests /tmp/devbin/ 2>/dev/null
nvidia-smi -L > $R/host.txt 2>&1; nproc >> $R/host.txt
timeout 300 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt
tail -3 $R/gpu_tests.txt
exports_cpu_vs_cuda demo armadillo_bunny bone_scaffold
