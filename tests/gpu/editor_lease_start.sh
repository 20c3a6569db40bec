# Sourced by the one-lease scripts of the editor (run_splat_kinds.sh, run_host_path.sh; run from
# the project root on the device): the X runtime of make-runtime.sh --x11 --pack and Xvfb started
# (.devrt/on-device.sh), the editor's libraries the host lacks (.devrt/libs.tar.xz) on the
# library path, every binary in .devrt/bin/*.xz unpacked, the host described in $OUT/r/gpu.txt.
# Sets B (binaries), S (scenes) and R (results) and the test data's environment; ends the
# script when no display came up.
source .devrt/on-device.sh
mkdir -p /tmp/devlib && tar xJf .devrt/libs.tar.xz -C /tmp/devlib
export LD_LIBRARY_PATH=/tmp/devlib:$LD_LIBRARY_PATH
for f in .devrt/bin/*.xz; do xz -dkf "$f" && chmod +x "${f%.xz}"; done
B=.devrt/bin; S=assets/scenes; R=$OUT/r; mkdir -p $R
export STRATA_ASSETS=$PWD/assets STRATA_TEST_DATA=$PWD/tests/data
nvidia-smi --query-gpu=name,memory.total --format=csv,noheader > $R/gpu.txt 2>&1; nproc >> $R/gpu.txt
[ -n "$DISPLAY" ] || { echo "no display" > $R/editor.txt; exit 1; }
