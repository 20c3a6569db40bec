#!/bin/bash
# The thirty-sixth session's lease, first call (headless .devrt with bin/strata.xz,
# strata_gpu_tests.xz, strata_gpu_gl_tests.xz): the libraries the host lacks into /tmp/devlib and
# the binaries into /tmp/devbin for run_session36_editor.sh (the packed X runtime alone).
# Results in $OUT/r: gpu_tests.txt (CUDA against the CPU), exports.txt (both backends' files
# compared), merge_steps.txt (armadillo - bunny at 4096 cells on one GPU: the merge's steps,
# the sort now timed apart from the index).
source tests/gpu/devrt_start.sh
mkdir -p /tmp/devbin && cp $B/strata $B/strata_gpu_gl_tests /tmp/devbin/
nvidia-smi -L > $R/host.txt 2>&1; nproc >> $R/host.txt
timeout 300 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt
tail -3 $R/gpu_tests.txt
exports_cpu_vs_cuda demo armadillo_bunny
/usr/bin/time -f "wall %e s, peak %M KB" timeout 200 $B/strata export $S/armadillo_bunny.strata.json \
  --resolution 4096 --backend cuda -q -o /tmp/ab4096.stl --report $R/ab4096.json > $R/merge_steps.txt 2>&1
echo "rc $?" >> $R/merge_steps.txt; rm -f /tmp/ab4096.stl
python3 -c "
import json; r=json.load(open('$R/ab4096.json'))
def find(d,k):
  if isinstance(d,dict):
    for a,b in d.items():
      if a==k: print(a,b)
      else: find(b,k)
  elif isinstance(d,list):
    for x in d: find(x,k)
find(r,'stages'); find(r,'merge_steps')" >> $R/merge_steps.txt 2>&1
cat $R/merge_steps.txt
