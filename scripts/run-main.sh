#!/usr/bin/env bash
# The main job: installs what is needed, builds, runs the drum-cleat deck on its default
# parameters (results/drum_cleat.h5 + .xmf) and plots it (results/drum_cleat_*.png).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
./build/tirefe inputs/drum_cleat.lua   # a progress line on a terminal, none in a log
./build/tirefe --views results/drum_cleat.h5   # the frames' views, for the XDMF index
/usr/bin/python3 post/plot_drum_cleat.py results/drum_cleat.h5
