#!/bin/bash
# The thirty-fifth session's second call on the same warm machine, the X runtime carried
# (make-runtime.sh --x11 --pack) with bin/strata.xz only: the libraries the host lacks are those
# the first call (run_session35.sh) unpacked into /tmp/devlib. Results go to $OUT/r:
# - ghost_interop.png, ghost_host.png: a plate whose two cutters stick out of it, ghosts shown
#   (now evaluated after the result is published): drawn whole through both paths;
# - editor.txt: edit-to-screen (#11: --measure-latency 12, the demo and armadillo - bunny at 512
#   and 1024 cells, interop and the host path), each with the frame built while the engine works
#   (--edit-wait 8, the default) and with the result drawn by the frame after its arrival
#   (--edit-wait 0), alternating;
# - ghost_latency.txt: moving a cutter whose ghost reaches beyond the result's grid, ghosts shown.
source tests/gpu/devrt_x_start.sh
ghost_shots
{
for res in 512 1024; do
  for via in "" --no-interop; do
    for wait in 8 0; do
      latency strata $S/demo.strata.json "bolt hole front left" $res --edit-wait $wait $via
      latency strata $S/armadillo_bunny.strata.json bunny $res --edit-wait $wait $via
    done
  done
done
} > $R/editor.txt 2>&1
grep -E "^(==|latency)" $R/editor.txt
{
for wait in 8 0; do
  latency strata /tmp/rod.strata.json "long pin" 512 --edit-wait $wait --ghosts
done
} > $R/ghost_latency.txt 2>&1
grep -E "^(==|latency)" $R/ghost_latency.txt
