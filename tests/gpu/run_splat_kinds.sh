#!/bin/bash
# One lease (issue #11, twenty-eighth session): the editor's edit-to-screen time on the GPU host
# with each way of drawing splats (--splats quads, points, compute and auto), with CUDA-GL
# interop at 512 and 1024 cells, and the host path; the GPU's time per splat of each kind; the
# frame times while orbiting; screenshots of the demo drawn as quads and by compute (compared
# here); the headless render tests (points and compute against quads) on the NVIDIA driver; the
# GPU tests. Carried in .devrt: the X runtime of make-runtime.sh --x11 --pack, libs.tar.xz (the
# editor's libraries the host lacks), bin/strata.xz, bin/strata_gpu_tests.xz,
# bin/strata_gpu_gl_tests.xz, bin/strata_ui_tests.xz. Results go to $OUT/r as they come.
source tests/gpu/editor_lease_start.sh
for t in strata_ui_tests:HeadlessRender.* strata_gpu_gl_tests:* strata_gpu_tests:*; do
  bin=${t%%:*}
  [ -x $B/$bin ] || continue
  timeout 240 $B/$bin --gtest_filter="${t#*:}" > $R/$bin.txt 2>&1; echo "$bin rc $?" >> $R/$bin.txt
  tail -2 $R/$bin.txt
done
latency() {  # scene leaf resolution splats [options]
  echo "== latency $(basename $1) '$2' $3 --splats $4 $5"
  timeout 120 $B/strata edit $1 --measure-latency 12 --move-leaf "$2" --resolution $3 --backend cuda --splats $4 $5 2>&1 | grep -E "^(first image|latency|strata)"
  local rc=${PIPESTATUS[0]}; [ $rc = 0 ] || echo "rc $rc"
}
{
for res in ${RESOLUTIONS:-512 1024}; do
  for splats in ${SPLATS:-quads points compute auto}; do
    latency $S/demo.strata.json "bolt hole front left" $res $splats
    latency $S/armadillo_bunny.strata.json bunny $res $splats
  done
  latency $S/demo.strata.json "bolt hole front left" $res auto --no-interop
  latency $S/armadillo_bunny.strata.json bunny $res auto --no-interop
done
for splats in quads auto; do
  latency $S/demo.strata.json "bolt hole front left" 2048 $splats
  latency $S/armadillo_bunny.strata.json bunny 2048 $splats
done
for splats in quads auto; do
  echo "== frames demo 1024 --splats $splats"
  timeout 120 $B/strata edit $S/demo.strata.json --measure-frames 5 --resolution 1024 --backend cuda --splats $splats 2>&1 | tail -6
done
for res in 512 1024; do
  echo "== drag demo $res"
  timeout 120 $B/strata edit $S/demo.strata.json --measure-latency 12 --move-leaf "bolt hole front left" --drag --resolution $res --backend cuda 2>&1 | grep -E "^(drag:|strata)"
done
for splats in quads compute; do
  timeout 60 $B/strata edit $S/demo.strata.json --resolution 512 --backend cuda --splats $splats --screenshot $R/demo-$splats.png 2>&1 | tail -1
done
} > $R/editor.txt 2>&1
grep -E "^(==|latency|splats drawn|drag:|orbiting|still|at rest)" $R/editor.txt
