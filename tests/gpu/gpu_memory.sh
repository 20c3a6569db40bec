# Sourced by the lease scripts beside it: each GPU's memory in use sampled every 100 ms while a
# command runs. gpu_sampler_start before the command, gpu_sampler_stop after it; gpumax prints
# each GPU's peak (MiB) over the last sampling.
gpu_sampler_start() {
  nvidia-smi --query-gpu=index,memory.used --format=csv,noheader,nounits -lms 100 > /tmp/mem.txt 2>/dev/null &
  GPU_SAMPLER=$!
}
gpu_sampler_stop() {
  kill $GPU_SAMPLER 2>/dev/null; wait $GPU_SAMPLER 2>/dev/null
}
gpumax() { python3 -c "
import collections; m=collections.defaultdict(int)
for l in open('/tmp/mem.txt'):
  p=[x.strip() for x in l.split(',')]
  if len(p)==2 and p[1].isdigit(): m[p[0]]=max(m[p[0]],int(p[1]))
print('GPU peak MiB', dict(m))"; }
