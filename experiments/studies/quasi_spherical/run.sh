#!/bin/sh
# Stationary shape spectrum of a quasi-spherical vesicle (docs/fluctuations.md, "Quasi-spherical
# vesicle"): the unit sphere of experiments/vesicle-sphere.prm (kappa = 1, H0 = 0, fixed volume)
# at k_BT > 0 with a fixed tau, and the same run at k_BT = 0 for the discrete sphere's own
# (cubic) deformation. One run at a time on one core, about 25 minutes in all; writes
# results/quasi_spherical/<case>/ and prints the tables of experiments/studies/quasi_spherical/output.txt.
# Usage: experiments/studies/quasi_spherical/run.sh [build/membrane-flow]
set -e
exe=${1:-build/membrane-flow}
out=results/quasi_spherical
here=$(dirname "$0")
run() { # name cells weight kT tau steps
  nice "$exe" --quiet --overwrite --set "Mesh/Cells per side=$2" --set "Material/Line tension=1" \
    --set "Material/Transition length=0.2" --set "Shape/Grid control weight=$3" \
    --set "Material/Temperature=$4" --set "Time stepping/Adaptive=false" --set "Time stepping/Time step=$5" \
    --set "Time stepping/End time=100" --set "Time stepping/Maximum steps=$6" --set "Output/Write VTU=false" \
    --set "Output/Directory=$out/$1" experiments/vesicle-sphere.prm
}
run n8_static 8 0.3 0 1e-3 300
run n8_tau1e-3 8 0.3 1e-4 1e-3 6000
run n8_tau5e-4 8 0.3 1e-4 5e-4 6000
run n16_static 16 0.5 0 3e-4 300
run n16_tau3e-4 16 0.5 2e-5 3e-4 2700
for case in n8_tau1e-3 n8_tau5e-4; do
  echo "== $case"
  /usr/bin/python3 "$here/analyze.py" "$out/$case/statistics.txt" --kT 1e-4 --static "$out/n8_static/statistics.txt"
done
echo "== n16_tau3e-4"
/usr/bin/python3 "$here/analyze.py" "$out/n16_tau3e-4/statistics.txt" --kT 2e-5 --skip 300 \
  --static "$out/n16_static/statistics.txt"
