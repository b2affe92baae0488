#!/usr/bin/env bash
# Install what hvi needs, build it (Release) and run the fast test tier.
# Long verification runs carry the ctest label 'long': run them with
#   ctest --test-dir build -L long
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
ctest --test-dir "$HVI_BUILD" --output-on-failure -LE long --parallel "$(nproc)"
