#!/bin/bash
# One lease (thirty-first session, issue #15), run from the project root on the device with
# .devrt carried (make-runtime.sh without --x11; libs.tar.xz: the libraries the host lacks;
# bin/*.xz: strata, strata_base (before the read-back beside the check), strata_base0 (before the
# estimate followed the workers' memory), strata_gpu_tests). Results go to $OUT/r:
# - gpu_tests.txt: CUDA against the CPU;
# - estimate.txt: `--gpus 2` on one device, the estimate's tiles (printed before it starts;
#   refused by --max-memory so that nothing runs) against the tiles the export then uses;
# - export.txt: armadillo - bunny at 4096 cells streamed, new and base alternating: stages, wall,
#   peak, files compared byte for byte.
source tests/gpu/devrt_start.sh
nvidia-smi -L > $R/host.txt 2>&1; nproc >> $R/host.txt; free -g >> $R/host.txt
timeout 200 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt
tail -3 $R/gpu_tests.txt
stages() { python3 -c "import json;d=json.load(open('$1'));print(d['tiles'], 'tiles', ' '.join('%s %.3f'%(s['name'],s['seconds']) for s in d['stages']), 'triangles', d['check']['triangles'], 'passed', d['check']['passed'])"; }
for scene in bone_scaffold armadillo_bunny; do
  for bin in strata_base0 strata; do
    for mode in "" "--stream"; do
      echo "== $scene 4096 $bin --gpus 2 $mode" >> $R/estimate.txt
      timeout 120 $B/$bin export $S/$scene.strata.json --resolution 4096 --backend cuda --gpus 2 $mode \
        --max-memory 100M -o /tmp/e.stl >> $R/estimate.txt 2>&1
    done
  done
  /usr/bin/time -f "wall %e s peak %M KiB" -o /tmp/t.txt timeout 200 $B/strata export $S/$scene.strata.json \
    --resolution 4096 --backend cuda --gpus 2 --stream -q -o /tmp/e.stl --report /tmp/e.json > /tmp/e.log 2>&1
  echo "   ran --gpus 2 --stream: rc $? $(cat /tmp/t.txt | tail -1) | $(stages /tmp/e.json 2>&1 | tail -1)" >> $R/estimate.txt
  rm -f /tmp/e.stl
done
cat $R/estimate.txt
for round in 1 2; do
  for bin in strata_base strata; do
    /usr/bin/time -f "wall %e s peak %M KiB" -o /tmp/t.txt timeout 200 $B/$bin export $S/armadillo_bunny.strata.json \
      --resolution 4096 --backend cuda --stream -q -o /tmp/x-$bin.stl --report /tmp/x-$bin.json > /tmp/x.log 2>&1
    echo "== $bin round $round: rc $? $(tail -1 /tmp/t.txt) | $(stages /tmp/x-$bin.json 2>&1 | tail -1)" >> $R/export.txt
  done
  cmp -s /tmp/x-strata.stl /tmp/x-strata_base.stl && echo "   same bytes" >> $R/export.txt || echo "   DIFFER" >> $R/export.txt
  rm -f /tmp/x-*.stl
done
cat $R/export.txt
