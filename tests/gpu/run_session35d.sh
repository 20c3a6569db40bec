#!/bin/bash
# The thirty-fifth session's fifth lease, first call (headless .devrt, bin/strata.xz): the
# libraries into /tmp/devlib and strata into /tmp/devbin for run_session35d_editor.sh.
source tests/gpu/devrt_start.sh
mkdir -p /tmp/devbin && cp $B/strata /tmp/devbin/
nvidia-smi -L; nproc
