#!/bin/bash
# Edit-to-screen of the demo at 1024 cells on the H200, this session's build against an earlier
# one (Nov 30, bin/strata_base.xz), alternating, through the host path and interop. Two calls on
# one lease: `bash tests/gpu/run_session38_ab.sh unpack` with a headless .devrt (libs.tar.xz,
# bin/strata.xz, bin/strata_base.xz) puts the libraries and binaries in /tmp/devlib and
# /tmp/devbin; then `bash tests/gpu/run_session38_ab.sh` with the packed X runtime measures.
if [ "$1" = unpack ]; then
  mkdir -p /tmp/devlib && tar xJf .devrt/libs.tar.xz -C /tmp/devlib
  mkdir -p /tmp/devbin && for b in strata strata_base; do
    xz -dc .devrt/bin/$b.xz > /tmp/devbin/$b && chmod +x /tmp/devbin/$b
  done
  ls /tmp/devbin
  exit 0
fi
DEVBIN=/tmp/devbin source tests/gpu/devrt_x_start.sh > /dev/null 2>&1
for i in 1 2; do for bin in strata_base strata; do
  latency $bin $S/demo.strata.json "bolt hole front left" 1024 --no-interop
  latency $bin $S/demo.strata.json "bolt hole front left" 1024
done; done 2>&1 | grep -E "^(==|latency)" | cut -c1-110
