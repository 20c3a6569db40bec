#!/bin/bash
# One lease on a host with two GPUs (sixteenth session, issue #15): `mpirun -np 2 strata export
# ... --distributed`, each process on its own GPU (the processes of a host take its GPUs in
# turn), against one process with one GPU: wall time, the processes' report, each GPU's peak
# memory, and the two files compared byte for byte. The host has no Open MPI: Debian's
# (openmpi-bin, libopenmpi3 and what they load) travels unpacked by on-device.sh from
# .devrt2/debs-x and runs from there (OPAL_PREFIX). Carried in .devrt2: the runtime,
# bin/strata.xz, bin/libstrata_mpi.so.xz (the plugin beside the binary). Results go to $OUT/r.
# BINS="strata strata_base" compares builds in one lease (bin/NAME.xz and
# bin/NAME-libstrata_mpi.so.xz for each but the first; the plugin is looked up beside the binary,
# so each build runs from a folder of its own).
BINS=${BINS:-strata}
LEASE_NO_TESTS=1 LEASE_BINARIES="$BINS" source tests/gpu/lease_start.sh
xz -dkf .devrt2/bin/libstrata_mpi.so.xz
for bin in $BINS; do
  mkdir -p /tmp/bins/$bin && cp .devrt2/bin/$bin /tmp/bins/$bin/strata
  if [ -f .devrt2/bin/$bin-libstrata_mpi.so.xz ]; then
    xz -dc .devrt2/bin/$bin-libstrata_mpi.so.xz > /tmp/bins/$bin/libstrata_mpi.so
  else
    cp .devrt2/bin/libstrata_mpi.so /tmp/bins/$bin/
  fi
done
export OPAL_PREFIX=$DEVRT_ROOT/usr PATH=$DEVRT_ROOT/usr/bin:$PATH
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# One host, no network fabric: shared memory between the processes.
export OMPI_MCA_btl=self,vader OMPI_MCA_pml=ob1 OMPI_MCA_osc=^ucx OMPI_MCA_plm_rsh_agent=false
orterun --version > $R/mpi.txt 2>&1
source tests/gpu/gpu_memory.sh
run() {  # name scene resolution options launcher... (the build: $bin)
  local name=$1 scene=$2 res=$3 options=$4; shift 4
  gpu_sampler_start
  /usr/bin/time -f "wall %e s, host peak %M KiB" -o /tmp/t.txt timeout 280 "$@" /tmp/bins/$bin/strata export \
    $S/$scene.strata.json --resolution $res --backend cuda -q -o /tmp/$name.stl $options \
    > /tmp/$name.txt 2>&1
  local rc=$?
  gpu_sampler_stop
  echo "== $scene $res $bin $name: rc $rc $(cat /tmp/t.txt | tail -1) | $(gpumax) | $(ls -l /tmp/$name.stl 2>/dev/null | awk '{print $5}') bytes"
  grep -E "^(time|processes|result)" /tmp/$name.txt
  [ $rc = 0 ] || tail -15 /tmp/$name.txt
}
{
for job in ${JOBS:-bone_scaffold:2048 bone_scaffold:4096 armadillo_bunny:4096}; do
 for bin in $BINS; do
  scene=${job%%:*} res=${job##*:}
  run one $scene $res "--gpus 1"
  run two $scene $res --distributed orterun -np 2 --bind-to none
  cmp -s /tmp/one.stl /tmp/two.stl && echo "   one process = two processes, byte for byte" ||
    echo "   FILES DIFFER (or missing)"
  # mpirun's default binding (a core or two a process): process 0's host stages on those.
  [ -n "$BOUND" ] && run bound $scene $res --distributed orterun -np 2
  rm -f /tmp/one.stl /tmp/two.stl /tmp/bound.stl
 done
done
} > $R/mpi_gpus.txt 2>&1
cat $R/mpi.txt | head -3
cat $R/mpi_gpus.txt
