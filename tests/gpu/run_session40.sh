#!/bin/bash
# The fortieth session's lease, first call (headless .devrt with bin/strata.xz,
# strata_gpu_tests.xz, strata_gpu_gl_tests.xz, libs.tar.xz and debs-x): CUDA against the CPU after
# the preview's settling pass (a result at rest on the scene's own lattice) and ghosts' windows
# of at most 512 cells; the bundled scenes exported by both backends and compared byte for byte
# (exports.txt). Copies the binaries to /tmp/devbin for run_session40_editor.sh.
source tests/gpu/devrt_start.sh
first_call_checks
exports_cpu_vs_cuda demo armadillo_bunny bone_scaffold
