#!/bin/bash
# The thirty-fifth session's third lease, second call: edit-to-screen of the session's first
# build (8b611d0: the frame built while the engine works) against its last (ghosts carried and
# moved, the renderer's kept image of the splats alone), alternating, two rounds, so that the
# host's own drift between leases is not read as a change. Results in $OUT/r/ab.txt.
[ -d /tmp/devbin ] || { echo "no /tmp/devbin: run run_session35c.sh first on this machine"; exit 1; }
DEVBIN=/tmp/devbin source tests/gpu/devrt_x_start.sh
{
for round in 1 2; do
  latency_set strata_base strata
  for bin in strata_base strata; do latency $bin /tmp/rod.strata.json "long pin" 512 --ghosts; done
done
} > $R/ab.txt 2>&1
grep -E "^(==|latency)" $R/ab.txt | sed -E 's/ \(cuda.*//'
