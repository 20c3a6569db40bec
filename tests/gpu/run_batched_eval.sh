#!/bin/bash
# One lease (tenth session, issue #13): leaves sampled in one batch. GPU tests (CUDA against the
# CPU); `strata eval` stage times; the editor's latency (the X runtime).
# Carried in .devrt: the X runtime of make-runtime.sh --x11 --pack, bin/*.xz. array200: a
# plate minus a 20 x 10 array of one hole (tests/data/array200.strata.json).
source .devrt/on-device.sh
for f in .devrt/bin/*.xz; do xz -dkf "$f"; done
chmod +x .devrt/bin/strata .devrt/bin/strata_gpu_tests
B=.devrt/bin; S=assets/scenes; D=tests/data; R=$OUT/r; mkdir -p $R
nvidia-smi --query-gpu=name,memory.total --format=csv,noheader > $R/gpu.txt 2>&1; nproc >> $R/gpu.txt
export STRATA_ASSETS=$PWD/assets STRATA_TEST_DATA=$PWD/tests/data
timeout 240 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt
# The benchmark travels in a lease of its own (.devrt2: no X runtime, which leaves no room):
#   source .devrt2/on-device.sh; xz -dk .devrt2/bin/strata_gpu_bench.xz; chmod +x ...;
#   strata_gpu_bench --resolutions 512,1024,2048 --cpu-max 512 --offset-cpu-max 0 \
#     --assets assets --data assets/meshes
{
for scene in $S/bone_scaffold_scaled_copy.strata.json $S/bone_scaffold.strata.json $D/array200.strata.json; do
  for bk in cuda cpu; do
    echo "== eval $(basename $scene) 512 $bk"
    $B/strata eval $scene --resolution 512 --backend $bk 2>&1 | grep -E "^(tessellate|sample|boolean|measure|total) "
  done
done
} > $R/eval.txt 2>&1
# Export stages and the boolean set: tests/gpu/run_host_stages.sh (the lease without X).
if [ -n "$DISPLAY" ]; then
  {
  for res in 512 1024; do
    echo "== latency array200 $res (moving the hole: 200 copies)"
    timeout 120 $B/strata edit $D/array200.strata.json --measure-latency 20 --move-leaf hole --resolution $res --backend cuda 2>&1 | tail -2
    echo "== latency scaffold copy $res (moving cell 111)"
    timeout 120 $B/strata edit $S/bone_scaffold_scaled_copy.strata.json --measure-latency 20 --move-leaf "cell 111" --resolution $res --backend cuda 2>&1 | tail -2
    echo "== latency demo $res (moving a bolt hole)"
    timeout 120 $B/strata edit $S/demo.strata.json --measure-latency 20 --move-leaf "bolt hole front left" --resolution $res --backend cuda 2>&1 | tail -2
  done
  } > $R/editor.txt 2>&1
else
  echo "no display" > $R/editor.txt
fi
tar czf $OUT/results.tgz -C $OUT r
