#!/bin/bash
# One lease (tenth session, issue #13): leaves sampled in one batch, a kept thread pool, one
# component pass in the merge. GPU tests (CUDA against the CPU); the benchmark (full evaluation
# after a warm-up); export stage times; the boolean set on both backends; the editor's latency.
# Carried in .devrt: bin/*.xz, data/array200.strata.json, data/setmeshes.tar.xz (meshes/: the
# OBJ files of ../shared/data/meshes but the two under assets/meshes; analytic/: tests/bench/make_boolean_set.py's).
source .devrt/on-device.sh
for f in .devrt/bin/*.xz; do xz -dkf "$f"; done
chmod +x .devrt/bin/strata .devrt/bin/strata_gpu_tests
B=.devrt/bin; S=assets/scenes; D=.devrt/data; R=$OUT/r; mkdir -p $R
tar xJf $D/setmeshes.tar.xz -C /tmp; M=/tmp/meshes; A=/tmp/analytic
cp assets/meshes/armadillo.obj assets/meshes/bunny.obj $M/  # the same files as ../shared's
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
for res in 512 1024 2048; do for scene in bone_scaffold_scaled_copy bone_scaffold; do for bk in cuda cpu; do
  [ $bk = cpu ] && [ $res = 2048 ] && continue
  /usr/bin/time -f "wall %e s, peak %M KiB" $B/strata export $S/$scene.strata.json --resolution $res \
    --backend $bk -q -o /tmp/x-$bk.stl --report /tmp/x.json > /tmp/x.txt 2>&1
  echo "== export $scene $res $bk: $(tail -1 /tmp/x.txt) $(python3 -c "import json;d=json.load(open('/tmp/x.json'));print(' '.join('%s %.3f'%(s['name'],s['seconds']) for s in d['stages']))")"
done; cmp -s /tmp/x-cuda.stl /tmp/x-cpu.stl && echo "   cuda = cpu, byte for byte"; done; done
} > $R/eval.txt 2>&1
for bk in cuda cpu; do
  bash tests/bench/boolean_set.sh $B/strata $M $A /tmp/set-$bk $bk 512 > $R/set-$bk.txt 2>&1
done
python3 - > $R/set-stages.txt 2>&1 <<'PY'
import json, glob, os
for bk in ("cuda", "cpu"):
    tot = {}
    for f in sorted(glob.glob("/tmp/set-%s/*.json" % bk)):
        for s in json.load(open(f))["stages"]:
            tot[s["name"]] = tot.get(s["name"], 0) + s["seconds"]
    print(bk, " ".join("%s %.3f" % kv for kv in tot.items()))
same = sum(open(f, "rb").read() == open(f.replace("set-cuda", "set-cpu"), "rb").read()
           for f in glob.glob("/tmp/set-cuda/*.stl"))
print("identical files cuda/cpu:", same, "of", len(glob.glob("/tmp/set-cuda/*.stl")))
PY
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
