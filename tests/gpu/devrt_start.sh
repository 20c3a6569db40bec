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
