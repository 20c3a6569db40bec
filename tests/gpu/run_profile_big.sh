#!/bin/bash
# One lease, no X runtime (fourteenth session, issues #13 and #15): what a process pays before
# any work on each backend (a tiny Boolean, three runs each; the driver's persistence mode; lazy
# against eager module loading), then `perf record -e cycles:u` of armadillo - bunny exported at
# 4096 cells on CUDA (the host stages of a 70 M triangle export). Carried in .devrt2:
# bin/strata.xz, bin/perf.tar.xz (/usr/bin/perf and the libraries it loads).
source .devrt2/on-device.sh
xz -dkf .devrt2/bin/strata.xz; chmod +x .devrt2/bin/strata
mkdir -p /tmp/perf && tar xJf .devrt2/bin/perf.tar.xz -C /tmp/perf
P="env LD_LIBRARY_PATH=/tmp/perf:$LD_LIBRARY_PATH /tmp/perf/perf"
B=.devrt2/bin; S=assets/scenes; R=$OUT/r; mkdir -p $R
export STRATA_ASSETS=$PWD/assets STRATA_TEST_DATA=$PWD/tests/data
{
nvidia-smi -q | grep -i -E "persistence|driver version|cuda version"
for i in 1 2 3; do for bk in cuda cpu; do
  /usr/bin/time -f "$bk: wall %e s" $B/strata boolean union tests/data/bunny.obj tests/data/eight.obj \
    --resolution 64 --backend $bk -q -o /tmp/tiny.stl 2>&1 | tail -1
done; done
for mode in EAGER LAZY; do
  CUDA_MODULE_LOADING=$mode /usr/bin/time -f "cuda, module loading $mode: wall %e s" $B/strata boolean \
    union tests/data/bunny.obj tests/data/eight.obj --resolution 64 --backend cuda -q -o /tmp/tiny.stl 2>&1 | tail -1
done
strace -f -c -o /tmp/strace.txt $B/strata boolean union tests/data/bunny.obj tests/data/eight.obj \
  --resolution 64 --backend cuda -q -o /tmp/tiny.stl > /dev/null 2>&1 && head -15 /tmp/strace.txt
} > $R/start.txt 2>&1
$P record -e cycles:u -F 999 -g -o /tmp/p.data $B/strata export $S/armadillo_bunny.strata.json \
  --resolution 4096 --backend cuda -q -o /tmp/x.stl --report /tmp/x.json > /dev/null 2>&1
python3 -c "import json;d=json.load(open('/tmp/x.json'));print(' '.join('%s %.3f'%(s['name'],s['seconds']) for s in d['stages']))" > $R/prof.txt
$P report -i /tmp/p.data --no-children --sort symbol 2>/dev/null | grep -E "^ +[0-9]" | head -40 | cut -c1-200 >> $R/prof.txt
$P report -i /tmp/p.data --children --sort symbol 2>/dev/null | grep -E "^ +[0-9]" | grep strata | head -40 | cut -c1-200 > $R/prof-children.txt
