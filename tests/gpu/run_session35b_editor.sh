#!/bin/bash
# The thirty-fifth session's second lease, second call, the packed X runtime carried alone (the
# libraries and binaries from run_session35b.sh in /tmp/devlib and /tmp/devbin). Results go to
# $OUT/r:
# - gl_tests.txt: the editor's pixels through interop, the host path and the CPU backend (the
#   renderer now keeps the image of the splats alone and draws ghosts and lines over it);
# - ghost_*.png: the plate with cutters sticking out, ghosts shown, through both paths;
# - editor.txt: edit-to-screen at 512 and 1024 cells, interop and the host path (the final build).
[ -d /tmp/devbin ] || { echo "no /tmp/devbin: run run_session35b.sh first on this machine"; exit 1; }
source .devrt/on-device.sh
export LD_LIBRARY_PATH=/tmp/devlib:$LD_LIBRARY_PATH
B=/tmp/devbin; S=assets/scenes; R=$OUT/r; mkdir -p $R
export STRATA_ASSETS=$PWD/assets STRATA_TEST_DATA=$PWD/tests/data
[ -n "$DISPLAY" ] || { echo "no display"; exit 1; }
timeout 240 $B/strata_gpu_gl_tests > $R/gl_tests.txt 2>&1; echo "gl tests rc $?" >> $R/gl_tests.txt
tail -3 $R/gl_tests.txt
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
  tail -1 $R/ghost_$path.txt
done
latency() {  # scene leaf resolution [--no-interop] [more]
  echo "== latency $(basename $1) '$2' $3 $4 $5"
  timeout 120 $B/strata edit $1 --measure-latency 12 --move-leaf "$2" --resolution $3 --backend cuda --splats auto $4 $5 2>&1 | grep -E "^(edit|first image|latency|strata)"
}
{
for res in 512 1024; do
  for via in "" --no-interop; do
    latency $S/demo.strata.json "bolt hole front left" $res $via
    latency $S/armadillo_bunny.strata.json bunny $res $via
  done
done
latency /tmp/rod.strata.json "long pin" 512 "" --ghosts
} > $R/editor.txt 2>&1
grep -E "^(==|latency)" $R/editor.txt
