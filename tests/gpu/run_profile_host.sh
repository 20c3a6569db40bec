#!/bin/bash
# Where one export's host side goes on the device host (sixteenth session, issues #13 and #15):
# `perf record -e cycles:u` of `strata export SCENE --resolution N --backend cuda`, then the
# symbols by self and by children time. Carried in .devrt2: the runtime (on-device.sh),
# bin/strata.xz, bin/perf.tar.xz (/usr/bin/perf and the libraries it loads).
#   usage: run_profile_host.sh SCENE RESOLUTION   (results in $OUT/r/prof-SCENE-N*.txt)
scene=${1:-armadillo_bunny} res=${2:-4096}
source .devrt2/on-device.sh
[ -x .devrt2/bin/strata ] || { xz -dkf .devrt2/bin/strata.xz && chmod +x .devrt2/bin/strata; }
mkdir -p /tmp/perf && tar xJf .devrt2/bin/perf.tar.xz -C /tmp/perf
P="env LD_LIBRARY_PATH=/tmp/perf:$LD_LIBRARY_PATH /tmp/perf/perf"
B=.devrt2/bin; S=assets/scenes; R=$OUT/r; mkdir -p $R
out=$R/prof-$scene-$res
# cycles:u where the host's perf events allow it, else the cpu-clock timer (a virtual machine).
for event in cycles:u cpu-clock; do
  $P record -e $event -F 499 -g -o /tmp/p.data $B/strata export $S/$scene.strata.json \
    --resolution $res --backend cuda -q -o /tmp/p.stl --report /tmp/p.json > $out-perf.log 2>&1 && break
done
python3 -c "import json;d=json.load(open('/tmp/p.json'));print(' '.join('%s %.3f'%(s['name'],s['seconds']) for s in d['stages']))" > $out.txt
$P report -i /tmp/p.data --no-children --sort symbol 2>/dev/null | grep -E "^ +[0-9]" | head -40 |
  cut -c1-220 >> $out.txt
$P report -i /tmp/p.data --children --sort symbol 2>/dev/null | grep -E "^ +[0-9]" | grep strata |
  head -50 | cut -c1-220 > $out-children.txt
rm -f /tmp/p.data /tmp/p.stl
