#!/bin/bash
# The thirty-fifth session's third lease, second call: edit-to-screen of the session's first
# build (8b611d0: the frame built while the engine works) against its last (ghosts carried and
# moved, the renderer's kept image of the splats alone), alternating, two rounds, so that the
# host's own drift between leases is not read as a change. Results in $OUT/r/ab.txt.
[ -d /tmp/devbin ] || { echo "no /tmp/devbin: run run_session35c.sh first on this machine"; exit 1; }
source .devrt/on-device.sh
export LD_LIBRARY_PATH=/tmp/devlib:$LD_LIBRARY_PATH
B=/tmp/devbin; S=assets/scenes; R=$OUT/r; mkdir -p $R
export STRATA_ASSETS=$PWD/assets STRATA_TEST_DATA=$PWD/tests/data
[ -n "$DISPLAY" ] || { echo "no display"; exit 1; }
cat > /tmp/rod.strata.json <<'SCENE'
{"format":"strata-scene","version":1,"unit":"millimetre","settings":{"resolution":512,"margin":0.05},
 "root":{"id":1,"name":"plate with pins","type":"difference","children":[
  {"id":2,"name":"plate","type":"box","size":[40,40,5]},
  {"id":3,"name":"long pin","type":"cylinder","radius":3,"height":60,"transform":{"translate":[8,8,0]}},
  {"id":4,"name":"cross rod","type":"cylinder","radius":1.5,"height":70,"transform":{"translate":[0,-8,0],"rotate":[0,90,0]}}]}}
SCENE
latency() {  # binary scene leaf resolution [--no-interop] [more]
  echo "== $1 $(basename $2) '$3' $4 $5 $6"
  timeout 120 $B/$1 edit $2 --measure-latency 12 --move-leaf "$3" --resolution $4 --backend cuda --splats auto $5 $6 2>&1 | grep -E "^latency"
}
{
for round in 1 2; do
  for res in 512 1024; do
    for via in "" --no-interop; do
      for bin in strata_base strata; do
        latency $bin $S/demo.strata.json "bolt hole front left" $res $via
        latency $bin $S/armadillo_bunny.strata.json bunny $res $via
      done
    done
  done
  for bin in strata_base strata; do latency $bin /tmp/rod.strata.json "long pin" 512 "" --ghosts; done
done
} > $R/ab.txt 2>&1
grep -E "^(==|latency)" $R/ab.txt | sed -E 's/ \(cuda.*//'
