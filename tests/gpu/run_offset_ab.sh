LEASE_BINARIES="strata_before strata_B16 strata_huge strata_gpu_tests" source tests/gpu/lease_start.sh
cat /sys/kernel/mm/transparent_hugepage/enabled /sys/kernel/mm/transparent_hugepage/defrag >> $R/gpus.txt
P=.devrt2/data/part.strata.json
run() { # name res threads scene tag
  STRATA_THREADS=$3 /usr/bin/time -f "%e %U %S %M" -o $R/t.txt $B/strata_$1 eval $4 --resolution $2 --backend cpu --report $R/r.json > /dev/null 2>&1
  python3 -c "
import json;d=json.load(open('$R/r.json'));m=[round(n.get('seconds',0),3) for n in d.get('nodes',[]) if n.get('kind') in ('round','offset','shell','fillet')]
print('$5 $1 res $2 threads $3 wall/user/sys/KB', open('$R/t.txt').read().strip(), 'modifiers', round(sum(m),3), len(m))" >> $R/offsets.txt
}
for k in 1 2 3; do for b in before B16 huge; do run $b 512 2 $P part; run $b 512 16 $P part; done; done
for k in 1 2; do for b in before B16 huge; do run $b 1024 16 $P part; done; done
for k in 1 2; do for b in before huge; do run $b 512 16 $S/bone_scaffold.strata.json scaffold; run $b 1024 16 $S/bone_scaffold.strata.json scaffold; done; done
$B/strata_before eval $P --resolution 1024 --backend cpu --surfels $R/a.ply >/dev/null 2>&1; $B/strata_huge eval $P --resolution 1024 --backend cpu --surfels $R/b.ply > /dev/null 2>&1; cmp $R/a.ply $R/b.ply && echo "surfels 1024 identical" >> $R/offsets.txt; rm -f $R/*.ply
grep AnonHuge /proc/meminfo >> $R/offsets.txt
cat $R/offsets.txt; tail -3 $R/gpu_tests.txt
