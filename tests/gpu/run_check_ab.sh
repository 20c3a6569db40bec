#!/bin/bash
# One lease (twenty-seventh session, issue #15): the streamed check's per-facet work, before and
# after, alternating twice: `strata export armadillo_bunny --resolution 4096 --backend cuda --stream`
# with bin/strata_base.xz (the previous build) and bin/strata.xz, wall, host peak, stage times, and
# the two files compared. Carried in .devrt: both binaries, libs.tar.xz, on-device.sh.
D=.devrt; source $D/on-device.sh
mkdir -p /tmp/devlib && tar xJf $D/libs.tar.xz -C /tmp/devlib; export LD_LIBRARY_PATH=/tmp/devlib:$LD_LIBRARY_PATH
for f in $D/bin/strata.xz $D/bin/strata_base.xz; do xz -dkf "$f"; done; chmod +x $D/bin/strata $D/bin/strata_base
export STRATA_ASSETS=$PWD/assets
for i in 1 2; do for bin in strata_base strata; do
/usr/bin/time -f "wall %e s peak %M KiB" -o /tmp/t.txt $D/bin/$bin export assets/scenes/armadillo_bunny.strata.json --resolution 4096 --backend cuda --stream -q -o /tmp/x-$bin.stl --report /tmp/x.json > /dev/null 2>&1
echo "$bin $(cat /tmp/t.txt) | $(python3 -c "import json;d=json.load(open('/tmp/x.json'));print(' '.join('%s %.3f'%(s['name'],s['seconds']) for s in d['stages']), d['check']['passed'])")"
done; cmp /tmp/x-strata_base.stl /tmp/x-strata.stl && echo SAME; done
