#!/bin/sh
# Stationary height spectrum of a flat patch (docs/fluctuations.md, "Validation: the stationary
# height spectrum"): the 16 x 16 patch of tests/inputs/thermal-patch-spectrum.prm at k_BT = 1e-4
# with three excess areas (the reference areas of the cosine mode (2,1) of amplitude 0, 2.2e-4,
# 3e-4) and three time steps, 4000 steps each, one run at a time on one core (about 20 minutes in
# all); then the mode-level model of the same constrained dynamics (modes.py, about a minute).
# Writes results/patch_spectrum/<case>/ and prints the tables of
# experiments/studies/patch_spectrum/output.txt.
# Usage: experiments/studies/patch_spectrum/run.sh [build/membrane-flow]
set -e
exe=${1:-build/membrane-flow}
out=results/patch_spectrum
here=$(dirname "$0")
run() { # name amplitude tau
  OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 nice "$exe" --quiet --overwrite --set "Initial shape/Cosine modes=$2 2 1" \
    --set "Time stepping/Time step=$3" --set "Time stepping/Maximum steps=4000" \
    --set "Output/Directory=$out/$1" tests/inputs/thermal-patch-spectrum.prm
}
run a2.2e-4_tau2e-5 2.2e-4 2e-5
run a3e-4_tau2e-5 3e-4 2e-5
run a3e-4_tau1e-5 3e-4 1e-5
run a3e-4_tau5e-6 3e-4 5e-6
run a0_tau2e-5 0 2e-5
for case in a2.2e-4_tau2e-5 a3e-4_tau2e-5 a3e-4_tau1e-5 a3e-4_tau5e-6 a0_tau2e-5; do
  echo "== $case"
  PYTHONPATH=python /usr/bin/python3 -m membrane_flow spectrum patch "$out/$case" --kT 1e-4 --skip 800
done
echo "== mode-level model"
/usr/bin/python3 "$here/modes.py"
