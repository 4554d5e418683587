#!/usr/bin/env bash
# Quick start: install the dependencies (Debian 12, as root), build, make the Python
# package importable (import membrane_flow with /usr/bin/python3), and run the default
# input. Run again, it skips what is done and rebuilds incrementally.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install_dependencies.sh
./scripts/build.sh
# The docs write the program as `membrane-flow`: put it on PATH (a link to build/).
if [ "$(id -u)" -eq 0 ]; then
  ln -sf "$(pwd)/build/membrane-flow" /usr/local/bin/membrane-flow
fi
./scripts/install_python_path.sh
./build/membrane-flow --overwrite experiments/default.prm
echo
echo "Open results/default/surface.pvd in ParaView; statistics in results/default/statistics.txt."
echo "Picture: /usr/bin/python3 -m membrane_flow render results/default/surface.pvd default.png (docs/visualization.md)."
