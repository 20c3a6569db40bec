#!/bin/bash
# One lease without the X runtime (tenth session, issue #13): GPU tests, the benchmark, export
# stage times of both scaffolds and armadillo - bunny, the boolean set on both backends, and a
# profile of one export's host side (perf, user cycles). Carried in .devrt2 (about 12 MiB):
# on-device.sh (make-runtime.sh's, paths to .devrt2), debs-gl, debs-x (libzip4, libglfw3,
# libepoxy0, libx11-6, libx11-data, libxcb1, libxau6, libxdmcp6, libbsd0, libmd0, libopenmesh1,
# libstb0: what the strata binary loads), bin/{strata,strata_gpu_tests,strata_gpu_bench}.xz
# (strata with its symbols: strip -g), bin/perf.tar.xz (/usr/bin/perf and the libraries it
# loads), data/setmeshes.tar.xz (see run_batched_eval.sh).
source .devrt2/on-device.sh
for f in .devrt2/bin/*.xz; do xz -dkf "$f"; done
chmod +x .devrt2/bin/strata .devrt2/bin/strata_gpu_tests .devrt2/bin/strata_gpu_bench
mkdir -p /tmp/perf && tar xJf .devrt2/bin/perf.tar.xz -C /tmp/perf
P="env LD_LIBRARY_PATH=/tmp/perf:$LD_LIBRARY_PATH /tmp/perf/perf"
B=.devrt2/bin; S=assets/scenes; R=$OUT/r; mkdir -p $R
tar xJf .devrt2/data/setmeshes.tar.xz -C /tmp; M=/tmp/meshes; A=/tmp/analytic
cp assets/meshes/armadillo.obj assets/meshes/bunny.obj $M/
export STRATA_ASSETS=$PWD/assets STRATA_TEST_DATA=$PWD/tests/data
timeout 240 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt
timeout 200 $B/strata_gpu_bench --resolutions 512,1024,2048 --cpu-max 512 --offset-cpu-max 0 \
  --assets assets --data assets/meshes > $R/bench.txt 2>&1; echo "bench rc $?" >> $R/bench.txt
{
for res in 512 1024 2048; do for scene in bone_scaffold_scaled_copy bone_scaffold armadillo_bunny; do for bk in cuda cpu; do
  [ $bk = cpu ] && [ $res = 2048 ] && continue
  /usr/bin/time -f "wall %e s, peak %M KiB" $B/strata export $S/$scene.strata.json --resolution $res \
    --backend $bk -q -o /tmp/x-$bk.stl --report /tmp/x.json > /tmp/x.txt 2>&1
  echo "== export $scene $res $bk: $(tail -1 /tmp/x.txt) $(python3 -c "import json;d=json.load(open('/tmp/x.json'));print(' '.join('%s %.3f'%(s['name'],s['seconds']) for s in d['stages']))")"
done; cmp -s /tmp/x-cuda.stl /tmp/x-cpu.stl && echo "   cuda = cpu, byte for byte"; done; done
} > $R/export.txt 2>&1
for bk in cuda cpu; do
  bash tests/bench/boolean_set.sh $B/strata $M $A /tmp/set-$bk $bk 512 > $R/set-$bk.txt 2>&1
done
python3 - > $R/set-stages.txt 2>&1 <<'PY'
import json, glob
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
$P record -e cycles:u -F 2999 -g -o /tmp/p.data $B/strata export $S/armadillo_bunny.strata.json \
  --resolution 1024 --backend cuda -o /tmp/x.stl > /dev/null 2>&1
$P report -i /tmp/p.data --no-children --sort symbol 2>/dev/null | grep -E "^ +[0-9]" | head -30 | cut -c1-170 > $R/prof.txt
tar czf $OUT/results.tgz -C $OUT r
