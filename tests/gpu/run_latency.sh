#!/bin/bash
# One lease (issue #11): the editor's edit-to-screen time on the GPU host, every edit's line
# (engine, splats, transfer, and the UI thread's time of each frame from the result on), with
# CUDA-GL interop and with the host path, at 512 and 1024 cells; the frame times while orbiting.
# Also the GPU tests (CUDA against the CPU, the interop copy in a window) and the levels of
# detail: the demo at 2048 cells in the editor and rendered. Splats drawn as quads, as points and
# as the renderer picks (--splats auto).
# Carried in .devrt: the X runtime of make-runtime.sh --x11 --pack, bin/strata.xz,
# bin/strata_gpu_tests.xz, bin/strata_gpu_gl_tests.xz.
source .devrt/on-device.sh
for f in .devrt/bin/*.xz; do xz -dkf "$f"; done
chmod +x .devrt/bin/*[^z]
B=.devrt/bin; S=assets/scenes; D=tests/data; R=$OUT/r; mkdir -p $R
nvidia-smi --query-gpu=name,memory.total --format=csv,noheader > $R/gpu.txt 2>&1; nproc >> $R/gpu.txt
export STRATA_ASSETS=$PWD/assets STRATA_TEST_DATA=$PWD/tests/data
# Each test binary where it was carried (the lease's 64 MiB may not hold them all).
if [ -x $B/strata_gpu_tests ]; then
  timeout 240 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt
  tail -4 $R/gpu_tests.txt
fi
[ -n "$DISPLAY" ] || { echo "no display" > $R/editor.txt; exit 1; }
if [ -x $B/strata_gpu_gl_tests ]; then
  timeout 120 $B/strata_gpu_gl_tests > $R/gpu_gl_tests.txt 2>&1; echo "gpu gl tests rc $?" >> $R/gpu_gl_tests.txt
  tail -3 $R/gpu_gl_tests.txt
fi
latency() {  # scene leaf resolution splats [--no-interop]
  echo "== latency $(basename $1) '$2' $3 --splats $4 $5"
  timeout 120 $B/strata edit $1 --measure-latency 12 --move-leaf "$2" --resolution $3 --backend cuda --splats $4 $5 2>&1 | grep -E "^(edit|first image|latency|strata)"
  local rc=${PIPESTATUS[0]}; [ $rc = 0 ] || echo "rc $rc"
}
{
# Splats as quads, as points, and as the renderer picks by its own timing (auto); LATENCY_SPLATS
# names fewer where the lease is short (e.g. "auto").
for res in 512 1024; do
  for splats in ${LATENCY_SPLATS:-quads points auto}; do
    latency $S/demo.strata.json "bolt hole front left" $res $splats
    latency $S/armadillo_bunny.strata.json bunny $res $splats
  done
  latency $D/array200.strata.json hole $res auto
  latency $S/demo.strata.json "bolt hole front left" $res auto --no-interop
  latency $S/armadillo_bunny.strata.json bunny $res auto --no-interop
done
# A drag: each move's result on screen (a draft where the full pass would be slow), then the
# release; and the edit-to-screen time in a smaller window (what the window's size costs a frame:
# under Xvfb the swap copies the window's pixels into the X server).
for res in 512 1024; do
  echo "== drag demo $res"
  timeout 120 $B/strata edit $S/demo.strata.json --measure-latency 12 --move-leaf "bolt hole front left" --drag --resolution $res --backend cuda 2>&1 | grep -E "^(drag|strata)"
  echo "== drag armadillo_bunny $res"
  timeout 120 $B/strata edit $S/armadillo_bunny.strata.json --measure-latency 12 --move-leaf bunny --drag --resolution $res --backend cuda 2>&1 | grep -E "^(drag|strata)"
  latency $S/demo.strata.json "bolt hole front left" $res auto "--width 800 --height 500"
done
for res in 2048; do
  latency $S/demo.strata.json "bolt hole front left" $res auto
  latency $S/armadillo_bunny.strata.json bunny $res auto
done
for res in 1024 2048 4096; do
  echo "== render demo $res 900x700"
  timeout 120 $B/strata render $S/demo.strata.json --resolution $res --width 900 --height 700 -o $R/demo-$res.png --backend cuda 2>&1 | tail -1
done
echo "== frames demo 1024"
timeout 120 $B/strata edit $S/demo.strata.json --measure-frames 5 --resolution 1024 --backend cuda 2>&1 | tail -6
} > $R/editor.txt 2>&1
cat $R/editor.txt | grep -E "^(==|first image|latency)"
