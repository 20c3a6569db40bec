#!/bin/bash
# One lease, no X runtime (fourteenth session, issue #13): the export's host stages before and
# after a change, on the device host's cores, binaries alternating run by run: GPU tests, then
# `strata export` of the issue's scaffold, armadillo - bunny and the rebuilt scaffold (stage
# times, wall, host peak, outputs compared byte for byte), the boolean set on both backends,
# and `--simplify 0.25` of the demo. Carried in .devrt2: bin/strata.xz (after),
# bin/strata_base.xz (before), bin/strata_gpu_tests.xz, data/setmeshes.tar.xz. Results go to
# $OUT/r as they come (a lease may end early). JOBS="scene:cells ..." replaces the exports'
# list; QUICK=1 leaves out the GPU tests, the boolean set and the simplification; CROSS=1 also
# exports each scene up to 2048 cells with the new binary on the CPU backend and compares files.
# DEVRT names the carried folder (.devrt2 unless set); its libs.tar.xz, where present, holds
# libraries the binaries need that the host lacks.
D=${DEVRT:-.devrt2}
source $D/on-device.sh
if [ -f $D/libs.tar.xz ]; then
  mkdir -p /tmp/devlib && tar xJf $D/libs.tar.xz -C /tmp/devlib
  export LD_LIBRARY_PATH=/tmp/devlib:$LD_LIBRARY_PATH
fi
for f in $D/bin/strata.xz $D/bin/strata_base.xz $D/bin/strata_gpu_tests.xz; do
  xz -dkf "$f"
done
chmod +x $D/bin/strata $D/bin/strata_base $D/bin/strata_gpu_tests
B=$D/bin; S=assets/scenes; R=$OUT/r; mkdir -p $R
export STRATA_ASSETS=$PWD/assets STRATA_TEST_DATA=$PWD/tests/data
nvidia-smi -L > $R/host.txt 2>&1; nproc >> $R/host.txt; free -g >> $R/host.txt; df -T /tmp >> $R/host.txt
[ -z "$QUICK" ] && { timeout 200 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt; }
stages() { python3 -c "import json;d=json.load(open('$1'));print(' '.join('%s %.3f'%(s['name'],s['seconds']) for s in d['stages']), 'sum %.3f'%sum(s['seconds'] for s in d['stages']), 'passed', d['check']['passed'])"; }
{
for job in ${JOBS:-bone_scaffold_scaled_copy:512 bone_scaffold_scaled_copy:1024 bone_scaffold_scaled_copy:2048 \
           armadillo_bunny:1024 armadillo_bunny:2048 bone_scaffold:1024 armadillo_bunny:4096}; do
  scene=${job%%:*} res=${job##*:}
  for round in 1 2; do for bin in strata_base strata; do
    /usr/bin/time -f "wall %e s peak %M KiB" -o /tmp/t.txt timeout 120 $B/$bin export $S/$scene.strata.json \
      --resolution $res --backend cuda -q -o /tmp/x-$bin.stl --report /tmp/x-$bin.json > /dev/null 2>&1
    echo "== $scene $res $bin #$round: $(cat /tmp/t.txt | tail -1) | $(stages /tmp/x-$bin.json 2>&1 | tail -1)"
  done; done
  cmp -s /tmp/x-strata_base.stl /tmp/x-strata.stl && echo "   before = after, byte for byte" || echo "   FILES DIFFER"
  # The new binary's file on the CPU backend (the reference) against its file on CUDA.
  if [ -n "$CROSS" ] && [ "$res" -le 2048 ]; then
    timeout 120 $B/strata export $S/$scene.strata.json --resolution $res --backend cpu -q \
      -o /tmp/x-cpu.stl > /dev/null 2>&1
    cmp -s /tmp/x-cpu.stl /tmp/x-strata.stl && echo "   cpu = cuda, byte for byte" || echo "   CPU AND CUDA DIFFER"
  fi
done
} > $R/export.txt 2>&1
if [ -n "$QUICK" ]; then tar czf $OUT/results.tgz -C $OUT r; exit 0; fi
tar xJf $D/data/setmeshes.tar.xz -C /tmp; M=/tmp/meshes; A=/tmp/analytic
cp assets/meshes/armadillo.obj assets/meshes/bunny.obj $M/
for bk in cuda cpu; do for bin in strata_base strata; do
  bash tests/bench/boolean_set.sh $B/$bin $M $A /tmp/set-$bin-$bk $bk 512 | tail -1 > $R/set-$bin-$bk.txt 2>&1
done; done
python3 - > $R/set-stages.txt 2>&1 <<'PY'
import json, glob
for run in ("strata_base-cuda", "strata-cuda", "strata_base-cpu", "strata-cpu"):
    tot = {}
    for f in sorted(glob.glob("/tmp/set-%s/*.json" % run)):
        for s in json.load(open(f))["stages"]:
            tot[s["name"]] = tot.get(s["name"], 0) + s["seconds"]
    print(run, " ".join("%s %.3f" % kv for kv in tot.items()), "sum %.3f" % sum(tot.values()))
PY
for bin in strata_base strata; do
  /usr/bin/time -f "wall %e s peak %M KiB" -o /tmp/t.txt timeout 120 $B/$bin export $S/demo.strata.json --resolution 512 \
    --backend cuda -q -o /tmp/s-$bin.stl --simplify 0.25 --report /tmp/s-$bin.json > /tmp/s.txt 2>&1
  echo "== simplify demo 512 $bin: $(cat /tmp/t.txt | tail -1) | $(python3 -c "import json;d=json.load(open('/tmp/s-$bin.json'));s=d['simplify'];print(s['triangles_before'],'->',s['triangles_after'],'in %.2f s (measure %.2f)'%(s['seconds'],s['measure_seconds']))")"
done > $R/simplify.txt 2>&1
cmp -s /tmp/s-strata_base.stl /tmp/s-strata.stl && echo "simplified files identical" >> $R/simplify.txt
tar czf $OUT/results.tgz -C $OUT r
