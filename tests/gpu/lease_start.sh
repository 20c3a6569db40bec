# Sourced by the one-lease scripts beside it (no X runtime; run from the project root on the
# device): the runtime carried in .devrt2 unpacked, the binaries named in LEASE_BINARIES (default
# strata and strata_gpu_tests) unpacked from .devrt2/bin/NAME.xz, the host described in
# $OUT/r/gpus.txt, and the GPU tests run into $OUT/r/gpu_tests.txt (unless LEASE_NO_TESTS is
# set). Sets B (binaries), S (scenes) and R (results) and the test data's environment.
source .devrt2/on-device.sh
for name in ${LEASE_BINARIES:-strata strata_gpu_tests}; do
  xz -dkf ".devrt2/bin/$name.xz" && chmod +x ".devrt2/bin/$name"
done
B=.devrt2/bin; S=assets/scenes; R=$OUT/r; mkdir -p $R
export STRATA_ASSETS=$PWD/assets STRATA_TEST_DATA=$PWD/tests/data
nvidia-smi -L > $R/gpus.txt 2>&1; nproc >> $R/gpus.txt; free -g >> $R/gpus.txt
if [ -z "$LEASE_NO_TESTS" ]; then
  timeout 240 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt
  tail -3 $R/gpu_tests.txt
fi
