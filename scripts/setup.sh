#!/usr/bin/env bash
# Quick start: install the dependencies (Debian 12, as root), build, and run the
# default input. Run again, it skips what is done and rebuilds incrementally.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install_dependencies.sh
./scripts/build.sh
./build/membrane-flow --overwrite experiments/default.prm
echo
echo "Open results/default/surface.pvd in ParaView; statistics in results/default/statistics.txt."
echo "Picture: scripts/render_surface.py results/default/surface.pvd default.png (docs/visualization.md)."
