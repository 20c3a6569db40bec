#!/bin/bash
# The thirty-seventh session's lease, second call, the packed X runtime carried alone (the
# libraries and binaries from run_session37.sh in /tmp/devlib and /tmp/devbin): the same as the
# thirty-fifth session's (the editor's pixels through interop and the host path: gl_tests.txt;
# the plate's ghosts: ghost_*.png; edit-to-screen at 512 and 1024 cells: editor.txt, in $OUT/r),
# on the build that holds the image shown while a finer resolution of the same parts is drawn.
exec bash tests/gpu/run_session35b_editor.sh
