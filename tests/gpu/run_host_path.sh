#!/bin/bash
# One lease (issue #11, twenty-ninth session): the editor's host path for device splats
# (`--no-interop`) with the worker's copies going straight into mapped GL buffers, page-locked
# (the default) and pageable (`--no-pinning`), against the previous build (bin/strata_base.xz:
# a copy into the worker's arrays, then an upload inside the frame), and CUDA-GL interop beside
# them; edit-to-screen at 512 and 1024 cells, each variant twice, alternating. Then the GPU GL
# tests (the editor's pixels through interop, the host path and the CPU backend). Carried in
# .devrt: the X runtime of make-runtime.sh --x11 --pack, libs.tar.xz, bin/strata.xz,
# bin/strata_base.xz, bin/strata_gpu_gl_tests.xz. Results go to $OUT/r as they come.
source tests/gpu/editor_lease_start.sh
latency() {  # name binary scene leaf resolution [options]
  echo "== $1 $(basename $3) $5 ${*:6}"
  timeout 120 $B/$2 edit $3 --measure-latency 12 --move-leaf "$4" --resolution $5 --backend cuda "${@:6}" 2>&1 | grep -E "^(latency|splats reach|strata)"
  local rc=${PIPESTATUS[0]}; [ $rc = 0 ] || echo "rc $rc"
}
{
for round in $(seq ${ROUNDS:-2}); do
  for res in ${RESOLUTIONS:-512 1024}; do
    for scene in "demo.strata.json:bolt hole front left" "armadillo_bunny.strata.json:bunny"; do
      f=$S/${scene%%:*}; leaf=${scene#*:}
      latency base strata_base $f "$leaf" $res --no-interop
      latency pageable strata $f "$leaf" $res --no-interop --no-pinning
      latency pinned strata $f "$leaf" $res --no-interop
      [ $round = 1 ] && latency interop strata $f "$leaf" $res
    done
  done
done
} > $R/editor.txt 2>&1
grep -E "^(==|latency|splats reach|rc)" $R/editor.txt | sed -E 's/ over 12 edits.*//'
timeout 240 $B/strata_gpu_gl_tests > $R/strata_gpu_gl_tests.txt 2>&1; echo "gl tests rc $?" >> $R/strata_gpu_gl_tests.txt
tail -3 $R/strata_gpu_gl_tests.txt
