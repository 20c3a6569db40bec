#!/bin/bash
# One lease (twenty-fifth session, issue #15): the export written in pieces (`--stream`) on the
# device host against the in-memory export, on the CUDA backend and the CPU's cores: wall, host
# peak and stage times of each, and every pair of files compared byte for byte (the CPU's
# in-memory file is the reference). Carried in $DEVRT (.devrt unless set): bin/strata.xz,
# bin/strata_gpu_tests.xz, libs.tar.xz (libraries the host lacks). JOBS="scene:cells ..."
# replaces the list. BASE=1: also the streamed CUDA export with bin/strata_base.xz (an earlier
# build) where it is carried, for a before / after in one lease. Results go to $OUT/r as they
# come (a lease may end early).
D=${DEVRT:-.devrt}
source $D/on-device.sh
if [ -f $D/libs.tar.xz ]; then
  mkdir -p /tmp/devlib && tar xJf $D/libs.tar.xz -C /tmp/devlib
  export LD_LIBRARY_PATH=/tmp/devlib:$LD_LIBRARY_PATH
fi
for f in $D/bin/strata.xz $D/bin/strata_gpu_tests.xz; do xz -dkf "$f"; done
chmod +x $D/bin/strata $D/bin/strata_gpu_tests
[ "$BASE" = 1 ] && [ -f $D/bin/strata_base.xz ] && xz -dkf $D/bin/strata_base.xz && chmod +x $D/bin/strata_base
B=$D/bin; S=assets/scenes; R=$OUT/r; mkdir -p $R
export STRATA_ASSETS=$PWD/assets STRATA_TEST_DATA=$PWD/tests/data
nvidia-smi -L > $R/host.txt 2>&1; nproc >> $R/host.txt; free -g >> $R/host.txt; df -T /tmp >> $R/host.txt
timeout 200 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt
stages() { python3 -c "import json;d=json.load(open('$1'));print(d['tiles'], 'tiles', ' '.join('%s %.3f'%(s['name'],s['seconds']) for s in d['stages']), 'triangles', d['check']['triangles'], 'passed', d['check']['passed'])"; }
{
for job in ${JOBS:-armadillo_bunny:1024 armadillo_bunny:2048 bone_scaffold:2048 armadillo_bunny:4096 bone_scaffold:4096}; do
  scene=${job%%:*} res=${job##*:}
  runs=("cpu " "cpu --stream" "cuda " "cuda --stream")
  [ -x $B/strata_base ] && runs+=("cuda --stream base")
  for run in "${runs[@]}"; do
    bk=${run%% *} flag=${run#* }; bin=strata
    [ "${flag% base}" != "$flag" ] && flag=${flag% base} && bin=strata_base
    name=$bk${flag:+-stream}; [ $bin = strata_base ] && name=$name-base
    [ "$bk" = cpu ] && [ "$res" -gt 2048 ] && continue
    /usr/bin/time -f "wall %e s peak %M KiB" -o /tmp/t.txt timeout 280 $B/$bin export $S/$scene.strata.json \
      --resolution $res --backend $bk $flag -q -o /tmp/x-$name.stl --report /tmp/x-$name.json > /tmp/x-$name.log 2>&1
    echo "== $scene $res $name: $(tail -1 /tmp/t.txt) | $(stages /tmp/x-$name.json 2>&1 | tail -1)"
  done
  ref=/tmp/x-cpu.stl; [ -f $ref ] || ref=/tmp/x-cuda.stl
  for name in cpu-stream cuda cuda-stream cuda-stream-base; do
    [ -f /tmp/x-$name.stl ] || continue
    cmp -s $ref /tmp/x-$name.stl && echo "   $name = $(basename $ref .stl), byte for byte" || echo "   $name DIFFERS from $(basename $ref .stl)"
  done
  rm -f /tmp/x-*.stl
done
} > $R/export.txt 2>&1
tar czf $OUT/results.tgz -C $OUT r
