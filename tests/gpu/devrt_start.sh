# Sourced by the one-lease scripts that carry .devrt (run from the project root on the device):
# its runtime set up (.devrt/on-device.sh: the GL packages, and Xvfb where the X runtime was
# packed), the libraries the host lacks (.devrt/libs.tar.xz) on the library path, every binary in
# .devrt/bin/*.xz unpacked. Sets B (binaries), S (scenes) and R (results: $OUT/r) and the test
# data's environment.
source .devrt/on-device.sh
mkdir -p /tmp/devlib && tar xJf .devrt/libs.tar.xz -C /tmp/devlib
export LD_LIBRARY_PATH=/tmp/devlib:$LD_LIBRARY_PATH
for f in .devrt/bin/*.xz; do xz -dkf "$f" && chmod +x "${f%.xz}"; done
B=.devrt/bin; S=assets/scenes; R=$OUT/r; mkdir -p $R
export STRATA_ASSETS=$PWD/assets STRATA_TEST_DATA=$PWD/tests/data

# The bundled scenes given, exported at 512 cells by both backends and compared byte for byte,
# into $R/exports.txt.
exports_cpu_vs_cuda() {
  for scene in "$@"; do
    for b in cpu cuda; do
      timeout 120 $B/strata export $S/$scene.strata.json --resolution 512 --backend $b -q -o /tmp/$b.stl > /tmp/$b.log 2>&1
      echo "== $scene 512 $b: rc $?" >> $R/exports.txt
    done
    cmp -s /tmp/cpu.stl /tmp/cuda.stl && echo "   CPU = CUDA, byte for byte" >> $R/exports.txt || echo "   FILES DIFFER" >> $R/exports.txt
    rm -f /tmp/cpu.stl /tmp/cuda.stl
  done
  cat $R/exports.txt
}

# A lease's first call: the binaries kept in /tmp/devbin for its editor call (devrt_x_start.sh),
# the host described ($R/host.txt), the GPU tests run ($R/gpu_tests.txt; the last lines shown).
first_call_checks() {
  mkdir -p /tmp/devbin && cp $B/strata $B/strata_gpu_gl_tests /tmp/devbin/ 2>/dev/null
  nvidia-smi -L > $R/host.txt 2>&1; nproc >> $R/host.txt
  timeout 300 $B/strata_gpu_tests > $R/gpu_tests.txt 2>&1; echo "gpu tests rc $?" >> $R/gpu_tests.txt
  tail -3 $R/gpu_tests.txt
}
