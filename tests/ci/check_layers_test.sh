#!/usr/bin/env bash
# .ci/check_layers passes on the real tree and catches each kind of forbidden include in a
# scratch copy of the folder layout.
set -euo pipefail
repo="$1"
"$repo/.ci/check_layers" "$repo" > /dev/null
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
mkdir -p "$scratch/engine/geometry" "$scratch/engine/util" "$scratch/ui" "$scratch/gpu"
expect_failure() {  # file, line, what the message must say
  printf '%s\n' "$2" > "$scratch/$1"
  if out=$("$repo/.ci/check_layers" "$scratch"); then
    echo "not caught: $2 in $1"; exit 1
  fi
  grep -q "$3" <<< "$out" || { echo "wrong message for $2: $out"; exit 1; }
  rm "$scratch/$1"
}
expect_failure engine/geometry/a.h '#include "engine/document/node.h"' "engine/geometry may not include engine/document"
expect_failure engine/util/b.cpp '#include <imgui.h>' "engine/ may not include"
expect_failure engine/util/c.h '#include <cuda_runtime.h>' "engine/ may not include"
expect_failure engine/util/d.h '#include "gpu/cuda_backend.h"' "engine/ may not include"
expect_failure ui/e.cpp '#include "gpu/cuda_backend.h"' "ui/ may not include"
expect_failure gpu/f.cu '#include "ui/editor.h"' "gpu/ may not include"
mkdir -p "$scratch/engine/newfolder"
expect_failure engine/newfolder/g.h '#include "engine/util/error.h"' "not in .ci/check_layers' table"
"$repo/.ci/check_layers" "$scratch" > /dev/null
echo "check_layers catches every forbidden include"
