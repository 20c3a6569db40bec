# Sourced by the one-lease scripts of the editor (run_splat_kinds.sh, run_host_path.sh; run from
# the project root on the device): the X runtime of make-runtime.sh --x11 --pack and Xvfb started
# (.devrt/on-device.sh), the editor's libraries the host lacks (.devrt/libs.tar.xz) on the
# library path, every binary in .devrt/bin/*.xz unpacked, the host described in $OUT/r/gpu.txt.
# Sets B (binaries), S (scenes) and R (results) and the test data's environment; ends the
# script when no display came up.
source tests/gpu/devrt_start.sh
nvidia-smi --query-gpu=name,memory.total --format=csv,noheader > $R/gpu.txt 2>&1; nproc >> $R/gpu.txt
[ -n "$DISPLAY" ] || { echo "no display" > $R/editor.txt; exit 1; }
