#!/usr/bin/env bash
# Kills N runs of tests/restart_deck.lua with SIGKILL at random instants (20 ms to 1.5 s
# in) and checks every result file and checkpoint they leave: each dataset reads, the
# rows of a group agree, no row of zeros, the XDMF index names only what the file holds.
# The suite runs 24 kills; this runs as many as asked (default 300), against build/tirefe
# or the tirefe given second.
#   scripts/kill-test.sh [N] [TIREFE]
set -euo pipefail
cd "$(dirname "$0")/.."
export TIREFE_KILLS="${1:-300}"
if [ $# -ge 2 ]; then export TIREFE_KILL_BINARY="$(realpath "$2")"; fi
build/tests/tirefe_tests "[kill]"
