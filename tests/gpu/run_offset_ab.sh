# One lease (run from the project root on the device): the CPU backend's offsets and the exports
# of modifier scenes, A/B between two builds carried in .devrt2/bin (strata_before: the session's
# start; strata: now), with the GPU tests first (lease_start.sh). Prints a table into
# $OUT/r/offsets.txt: wall, user and system seconds and peak KB of each run, and whether the
# two builds wrote the same file. tests/data/pen_holder.strata.json is an artist's part (a
# round and a fillet); the rebuilt bone scaffold has an offset of its femur.
LEASE_BINARIES="strata_before strata strata_gpu_tests" source tests/gpu/lease_start.sh
cat /sys/kernel/mm/transparent_hugepage/enabled >> $R/gpus.txt
P=tests/data/pen_holder.strata.json
run() { # build resolution threads scene tag backend
  STRATA_THREADS=$3 /usr/bin/time -f "%e %U %S %M" -o $R/t.txt $B/$1 export $4 --resolution $2 \
    --backend $6 -o $R/$5-$1-$2-$6.stl --report $R/r.json > /dev/null 2>&1
  echo "$5 $6 $1 res $2 threads $3 wall/user/sys/KB $(cat $R/t.txt) tiles $(python3 -c "
import json;d=json.load(open('$R/r.json'));print(d['tiles'], [(s['name'],round(s['seconds'],2)) for s in d['stages']])")" >> $R/offsets.txt
}
for k in 1 2; do for b in strata_before strata; do
  run $b 1024 16 $P pen cpu; run $b 1024 16 $S/bone_scaffold.strata.json scaffold cpu
  run $b 2048 16 $S/bone_scaffold.strata.json scaffold cuda
done; done
for t in pen-%s-1024-cpu scaffold-%s-1024-cpu scaffold-%s-2048-cuda; do
  a=$R/$(printf $t strata_before).stl; b=$R/$(printf $t strata).stl
  cmp -s $a $b && echo "$t: the same file" >> $R/offsets.txt || echo "$t: FILES DIFFER" >> $R/offsets.txt
done
rm -f $R/*.stl
cat $R/offsets.txt; tail -3 $R/gpu_tests.txt
