# Sourced by the editor scripts of a lease's second call, which carry the packed X runtime alone
# (make-runtime.sh --x11 --pack): the libraries the host lacks are in /tmp/devlib, unpacked by the
# lease's first call (devrt_start.sh). Sets B (the binaries: $DEVBIN, or .devrt/bin where the
# call carries strata.xz), S, R, the test data's environment; writes /tmp/rod.strata.json (a plate
# whose two cutters stick out of it on every side) and defines ghost_shots and latency.
[ -d /tmp/devlib ] || { echo "no /tmp/devlib: run the lease's first call on this machine first"; exit 1; }
source .devrt/on-device.sh
export LD_LIBRARY_PATH=/tmp/devlib:$LD_LIBRARY_PATH
if [ -n "$DEVBIN" ]; then
  B=$DEVBIN
else
  xz -dkf .devrt/bin/strata.xz && chmod +x .devrt/bin/strata
  B=.devrt/bin
fi
S=assets/scenes; R=$OUT/r; mkdir -p $R
export STRATA_ASSETS=$PWD/assets STRATA_TEST_DATA=$PWD/tests/data
[ -n "$DISPLAY" ] || { echo "no display"; exit 1; }
cat > /tmp/rod.strata.json <<'SCENE'
{"format":"strata-scene","version":1,"unit":"millimetre","settings":{"resolution":512,"margin":0.05},
 "root":{"id":1,"name":"plate with pins","type":"difference","children":[
  {"id":2,"name":"plate","type":"box","size":[40,40,5]},
  {"id":3,"name":"long pin","type":"cylinder","radius":3,"height":60,"transform":{"translate":[8,8,0]}},
  {"id":4,"name":"cross rod","type":"cylinder","radius":1.5,"height":70,"transform":{"translate":[0,-8,0],"rotate":[0,90,0]}}]}}
SCENE
# The plate's ghosts through interop and the host path: $R/ghost_interop.png, ghost_host.png.
ghost_shots() {
  for path in interop host; do
    extra=""; [ $path = host ] && extra="--no-interop"
    timeout 90 $B/strata edit /tmp/rod.strata.json --ghosts --backend cuda $extra --width 1280 --height 800 \
      --screenshot $R/ghost_$path.png > $R/ghost_$path.txt 2>&1; echo "rc $?" >> $R/ghost_$path.txt
    tail -2 $R/ghost_$path.txt
  done
}
# latency BINARY SCENE LEAF RESOLUTION [more options]: edit-to-screen of 12 moves of LEAF.
latency() {
  local bin=$1 scene=$2 leaf=$3 res=$4; shift 4
  echo "== latency $bin $(basename $scene) '$leaf' $res $*"
  timeout 120 $B/$bin edit $scene --measure-latency 12 --move-leaf "$leaf" --resolution $res --backend cuda --splats auto "$@" 2>&1 | grep -E "^(edit|first image|latency|strata)"
}
# latency_set BINARY...: the demo and armadillo - bunny at 512 and 1024 cells, through interop and
# the host path, each binary in turn for each.
latency_set() {
  for res in 512 1024; do
    for via in "" --no-interop; do
      for bin in "$@"; do
        latency $bin $S/demo.strata.json "bolt hole front left" $res $via
        latency $bin $S/armadillo_bunny.strata.json bunny $res $via
      done
    done
  done
}
