#!/bin/bash
# The thirty-fifth session's third lease, first call (headless .devrt, bin/strata.xz of the
# session's last build and bin/strata_base.xz of its first, 8b611d0): libraries into /tmp/devlib,
# both binaries into /tmp/devbin for run_session35c_editor.sh (the packed X runtime alone).
source tests/gpu/devrt_start.sh
mkdir -p /tmp/devbin && cp $B/strata $B/strata_base /tmp/devbin/
nvidia-smi -L > $R/host.txt 2>&1; nproc >> $R/host.txt; cat $R/host.txt
