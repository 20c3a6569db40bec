#!/bin/bash
# The thirty-fifth session's second lease, first call (headless .devrt with bin/strata.xz,
# strata_gpu_tests.xz, strata_gpu_gl_tests.xz): the libraries the host lacks into /tmp/devlib and
# the binaries into /tmp/devbin for the second call (run_session35b_editor.sh, which carries the
# packed X runtime alone). Results go to $OUT/r: gpu_tests.txt (CUDA against the CPU).
source tests/gpu/devrt_start.sh
mkdir -p /tmp/devbin && cp $B/strata $B/strata_gpu_gl_tests /tmp/devbin/
nvidia-smi -L > $R/host.txt 2>&1; nproc >> $R/host.txt
timeout 300 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt
tail -3 $R/gpu_tests.txt
