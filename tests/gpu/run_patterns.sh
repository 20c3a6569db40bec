#!/bin/bash
# One lease (ninth session): GPU tests; patterns and the thinnest wall on CUDA against the CPU;
# the editor with 200 array instances on the H200.
source .devrt/on-device.sh
for f in .devrt/bin/*.xz; do xz -dk "$f"; done; chmod +x .devrt/bin/strata .devrt/bin/strata_gpu_tests
B=.devrt/bin; S=assets/scenes; D=.devrt/data; R=$OUT/r; mkdir -p $R
nvidia-smi --query-gpu=name,memory.total --format=csv,noheader > $R/gpu.txt 2>&1; nproc >> $R/gpu.txt
export STRATA_ASSETS=$PWD/assets STRATA_TEST_DATA=$PWD/tests/data
timeout 240 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt
{
for scene in $S/flange_patterns.strata.json $D/array200.strata.json $S/bone_scaffold.strata.json; do
  for res in 512 1024; do for bk in cuda cpu; do
    echo "== eval $(basename $scene) $res $bk"
    $B/strata eval $scene --resolution $res --backend $bk 2>&1 | grep -E "^time|^result|thinnest|^stage|sample|boolean|measure "
  done; done
  for bk in cuda cpu; do
    /usr/bin/time -f "wall %e s" $B/strata export $scene --resolution 512 --backend $bk -q -o /tmp/p-$bk.stl > /tmp/p.txt 2>&1
    echo "== export $(basename $scene) 512 $bk: $(grep -E 'time|check|wall' /tmp/p.txt | tr '\n' ' ')"
  done
  cmp /tmp/p-cuda.stl /tmp/p-cpu.stl && echo "   cuda and cpu exports byte-identical"
done
} > $R/patterns.txt 2>&1
if [ -n "$DISPLAY" ]; then
  {
  for res in 512 1024; do
    echo "== latency array200 $res (moving the hole: 200 copies)"
    timeout 120 $B/strata edit $D/array200.strata.json --measure-latency 20 --move-leaf hole --resolution $res --backend cuda 2>&1 | tail -4
    echo "== latency flange $res (moving the bolt hole: 6 copies)"
    timeout 120 $B/strata edit $S/flange_patterns.strata.json --measure-latency 20 --move-leaf "bolt hole" --resolution $res --backend cuda 2>&1 | tail -4
  done
  echo "== frames array200 1024"
  timeout 120 $B/strata edit $D/array200.strata.json --measure-frames 8 --resolution 1024 --backend cuda --width 1400 --height 900 2>&1 | tail -6
  } > $R/editor.txt 2>&1
else
  echo "no display" > $R/editor.txt
fi
tar czf $OUT/results.tgz -C $OUT r
