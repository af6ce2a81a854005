#!/usr/bin/env bash
# The main job: installs what is needed, builds, runs the main deck and plots its results.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
./build/tirefe inputs/cantilever_elastica.lua
/usr/bin/python3 post/plot_results.py results/cantilever_elastica.h5
