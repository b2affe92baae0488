#!/usr/bin/env bash
# Install what hvi needs, build it, and run the default scene cases/demo.toml.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
out="${1:-$HVI_ROOT/runs/demo}"
"$HVI_BUILD/hvi" run "$HVI_ROOT/cases/demo.toml" --out "$out" --overwrite
