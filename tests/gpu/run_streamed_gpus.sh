#!/bin/bash
# One lease (twenty-seventh session, issue #15): the streamed export (`--stream`) with its tiles
# contoured by workers ahead of the merge, on one and two workers (`--gpus 1|2`: two GPUs on a
# two-GPU host, two workers sharing the one GPU elsewhere), against the previous build
# (bin/strata_base.xz: the tiles contoured and merged in turn on one thread) and the in-memory
# export: wall, host peak, stage times, each GPU's peak memory (nvidia-smi every 100 ms), and
# every file compared byte for byte with the in-memory one. Carried in $DEVRT (.devrt unless
# set): bin/strata.xz, bin/strata_base.xz, bin/strata_gpu_tests.xz, libs.tar.xz.
# JOBS="scene:cells ..." replaces the list; RUNS="name:binary:options,..." the runs of each (options
# joined by "+"; the first run is the one every file is compared with). Results go to $OUT/r as
# they come.
D=${DEVRT:-.devrt}
source $D/on-device.sh
if [ -f $D/libs.tar.xz ]; then
  mkdir -p /tmp/devlib && tar xJf $D/libs.tar.xz -C /tmp/devlib
  export LD_LIBRARY_PATH=/tmp/devlib:$LD_LIBRARY_PATH
fi
for f in $D/bin/*.xz; do xz -dkf "$f" && chmod +x "${f%.xz}"; done
B=$D/bin; S=assets/scenes; R=$OUT/r; mkdir -p $R
export STRATA_ASSETS=$PWD/assets STRATA_TEST_DATA=$PWD/tests/data
nvidia-smi -L > $R/host.txt 2>&1; nproc >> $R/host.txt; free -g >> $R/host.txt
timeout 200 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt
tail -3 $R/gpu_tests.txt
stages() { python3 -c "import json;d=json.load(open('$1'));print(d['tiles'], 'tiles', ' '.join('%s %.3f'%(s['name'],s['seconds']) for s in d['stages']), 'triangles', d['check']['triangles'], 'passed', d['check']['passed'], '| merge steps', ' '.join('%s %.2f'%(s['name'],s['seconds']) for s in d.get('merge_steps', [])))"; }
source tests/gpu/gpu_memory.sh
for job in ${JOBS:-armadillo_bunny:4096 bone_scaffold:4096}; do
  scene=${job%%:*} res=${job##*:}
  IFS=, read -ra runs <<< "${RUNS:-memory:strata:--gpus+1,base:strata_base:--stream,stream1:strata:--stream+--gpus+1,stream2:strata:--stream+--gpus+2}"
  names=()
  for run in "${runs[@]}"; do
    IFS=: read -r name bin options <<< "$run"; names+=("$name")
    set -- ${options//+/ }
    gpu_sampler_start
    /usr/bin/time -f "wall %e s peak %M KiB" -o /tmp/t.txt timeout 280 $B/$bin export $S/$scene.strata.json \
      --resolution $res --backend cuda "$@" -q -o /tmp/x-$name.stl --report /tmp/x-$name.json > /tmp/x-$name.log 2>&1
    rc=$?
    gpu_sampler_stop
    echo "== $scene $res $name ($*): rc $rc $(tail -1 /tmp/t.txt) | $(stages /tmp/x-$name.json 2>&1 | tail -1) | $(gpumax)" >> $R/export.txt
    [ $rc = 0 ] || tail -3 /tmp/x-$name.log >> $R/export.txt
  done
  first=${names[0]}
  for name in "${names[@]:1}"; do
    cmp -s /tmp/x-$first.stl /tmp/x-$name.stl && echo "   $name = $first, byte for byte" >> $R/export.txt || echo "   $name DIFFERS from $first (or missing)" >> $R/export.txt
  done
  rm -f /tmp/x-*.stl
done
cat $R/export.txt
