#!/usr/bin/env bash
# Runs every experiment of the paper (experiments/7*.prm, plus 7.4 C and D at sigma = 1000)
# and the closed vesicles (experiments/vesicle-*.prm, plus the small domain at sigma = 10) at full length into results/, then
# regenerates docs/experiments.md, the gallery and their pictures.
# About 35 minutes on 2 cores (the budding runs refine the mesh locally). Usage: scripts/run_experiments.sh [membrane-flow]
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${1:-build/membrane-flow}
for f in experiments/7*.prm experiments/vesicle-*.prm; do
  echo "running $f"
  "$exe" --quiet --overwrite "$f" | tail -n 3
done
"$exe" --quiet --overwrite --set "Material/Line tension=1000" --set "Output/Directory=results/7.4C-sigma1000" \
  experiments/7.4C-sigma630.prm | tail -n 3
"$exe" --quiet --overwrite --set "Material/Line tension=1000" --set "Output/Directory=results/7.4D-sigma1000" \
  experiments/7.4D-small-domain.prm | tail -n 3
"$exe" --quiet --overwrite --set "Material/Line tension=10" --set "Output/Directory=results/vesicle-small-domain-sigma10" \
  experiments/vesicle-small-domain.prm | tail -n 3
/usr/bin/python3 -m membrane_flow experiment-docs results docs
/usr/bin/python3 -m membrane_flow gallery results docs
