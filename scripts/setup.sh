#!/usr/bin/env bash
# Quick start: install the dependencies (Debian 12, as root), build, make the Python
# package importable (import membrane_flow with /usr/bin/python3), and run the default
# input. Run again, it skips what is done and rebuilds incrementally.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install_dependencies.sh
./scripts/build.sh
./scripts/install_python_path.sh
./build/membrane-flow --overwrite experiments/default.prm
echo
echo "Open results/default/surface.pvd in ParaView; statistics in results/default/statistics.txt."
