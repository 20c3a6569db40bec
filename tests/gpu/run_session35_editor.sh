#!/bin/bash
# The thirty-fifth session's second call on the same warm machine, the X runtime carried
# (make-runtime.sh --x11 --pack) with bin/strata.xz only: the libraries the host lacks are those
# the first call (run_session35.sh) unpacked into /tmp/devlib. Results go to $OUT/r:
# - ghost_interop.png, ghost_host.png: a plate whose two cutters stick out of it, ghosts shown
#   (now evaluated after the result is published): drawn whole through both paths;
# - editor.txt: edit-to-screen (#11: --measure-latency 12, the demo and armadillo - bunny at 512
#   and 1024 cells, interop and the host path), each with the frame built while the engine works
#   (--edit-wait 8, the default) and as before (--edit-wait 0: the frame waits for the result
#   before it starts), alternating;
# - ghost_latency.txt: moving a cutter whose ghost reaches beyond the result's grid, ghosts shown.
[ -d /tmp/devlib ] || { echo "no /tmp/devlib: run run_session35.sh first on this machine"; exit 1; }
source .devrt/on-device.sh
export LD_LIBRARY_PATH=/tmp/devlib:$LD_LIBRARY_PATH
xz -dkf .devrt/bin/strata.xz && chmod +x .devrt/bin/strata
B=.devrt/bin; S=assets/scenes; R=$OUT/r; mkdir -p $R
export STRATA_ASSETS=$PWD/assets STRATA_TEST_DATA=$PWD/tests/data
[ -n "$DISPLAY" ] || { echo "no display"; exit 1; }
cat > /tmp/rod.strata.json <<'SCENE'
{"format":"strata-scene","version":1,"unit":"millimetre","settings":{"resolution":512,"margin":0.05},
 "root":{"id":1,"name":"plate with pins","type":"difference","children":[
  {"id":2,"name":"plate","type":"box","size":[40,40,5]},
  {"id":3,"name":"long pin","type":"cylinder","radius":3,"height":60,"transform":{"translate":[8,8,0]}},
  {"id":4,"name":"cross rod","type":"cylinder","radius":1.5,"height":70,"transform":{"translate":[0,-8,0],"rotate":[0,90,0]}}]}}
SCENE
for path in interop host; do
  extra=""; [ $path = host ] && extra="--no-interop"
  timeout 90 $B/strata edit /tmp/rod.strata.json --ghosts --backend cuda $extra --width 1280 --height 800 \
    --screenshot $R/ghost_$path.png > $R/ghost_$path.txt 2>&1; echo "rc $?" >> $R/ghost_$path.txt
  tail -2 $R/ghost_$path.txt
done
latency() {  # scene leaf resolution wait [--no-interop] [more]
  echo "== latency $(basename $1) '$2' $3 wait $4 $5 $6"
  timeout 120 $B/strata edit $1 --measure-latency 12 --move-leaf "$2" --resolution $3 --backend cuda --splats auto --edit-wait $4 $5 $6 2>&1 | grep -E "^(edit|first image|latency|strata)"
}
{
for res in 512 1024; do
  for via in "" --no-interop; do
    for wait in 8 0; do
      latency $S/demo.strata.json "bolt hole front left" $res $wait $via
      latency $S/armadillo_bunny.strata.json bunny $res $wait $via
    done
  done
done
} > $R/editor.txt 2>&1
grep -E "^(==|latency)" $R/editor.txt
{
for wait in 8 0; do
  latency /tmp/rod.strata.json "long pin" 512 $wait "" --ghosts
done
} > $R/ghost_latency.txt 2>&1
grep -E "^(==|latency)" $R/ghost_latency.txt
