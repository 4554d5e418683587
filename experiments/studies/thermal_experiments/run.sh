#!/bin/sh
# The thermal experiments of docs/fluctuations.md ("Experiments"), one run at a time on one core
# (about 80 minutes in all), then their numbers (analyze.py) in results/thermal_experiments.json:
#   a flickering vesicle (experiments/thermal-flicker.prm);
#   nucleation from a metastable mixture (experiments/thermal-nucleation.prm): noise seed 1, its
#     deterministic control at Temperature = 0, seed 2 (to t = 0.3), and a shallower quench (mean
#     phi -0.74 instead of -0.77);
#   coarsening after nucleation (experiments/thermal-coarsening.prm, mean phi -0.62) and its
#     deterministic control (to t = 0.3);
#   domain budding (experiments/vesicle-domain-budding.prm, sigma = 50) at a fixed tau without and
#     with noise: grid control 0.1 (the file's) and 0.3, tau = 1e-3 and 5e-4, several k_BT and seeds.
#     Exit code 2 (a cell degenerates under too strong a noise) is a result here, not an error.
# Usage: experiments/studies/thermal_experiments/run.sh [build/membrane-flow]
set -e
exe=${1:-build/membrane-flow}
here=$(dirname "$0")
json=results/thermal_experiments.json
mkdir -p results
rm -f "$json"
"$exe" --quiet --overwrite experiments/thermal-flicker.prm
"$exe" --quiet --overwrite experiments/thermal-nucleation.prm
"$exe" --quiet --overwrite --set "Material/Temperature=0" \
  --set "Output/Directory=results/thermal-nucleation-T0" experiments/thermal-nucleation.prm
"$exe" --quiet --overwrite --set "Material/Noise seed=2" --set "Time stepping/End time=0.3" \
  --set "Output/Directory=results/thermal-nucleation-seed2" experiments/thermal-nucleation.prm
"$exe" --quiet --overwrite --set "Initial phase/Random min=-0.79" --set "Initial phase/Random max=-0.69" \
  --set "Output/Directory=results/thermal-nucleation-m0.74" experiments/thermal-nucleation.prm
"$exe" --quiet --overwrite experiments/thermal-coarsening.prm
"$exe" --quiet --overwrite --set "Material/Temperature=0" --set "Time stepping/End time=0.3" \
  --set "Output/Directory=results/thermal-coarsening-T0" experiments/thermal-coarsening.prm
bud() { # directory weight tau kT seed
  "$exe" --quiet --overwrite --set "Time stepping/Adaptive=false" --set "Time stepping/Time step=$3" \
    --set "Shape/Grid control weight=$2" --set "Material/Temperature=$4" --set "Material/Noise seed=$5" \
    --set "Output/Directory=results/$1" experiments/vesicle-domain-budding.prm || [ $? -eq 2 ]
}
bud budding-thermal/T0 0.1 1e-3 0 1
for seed in 1 2 3; do bud budding-thermal/kT2e-6-seed$seed 0.1 1e-3 2e-6 $seed; done
bud budding-thermal/kT1e-5-seed1 0.1 1e-3 1e-5 1
bud budding-thermal/kT1e-4-seed1 0.1 1e-3 1e-4 1
bud budding-thermal-gc0.3/T0 0.3 1e-3 0 1
for seed in 1 2 3; do bud budding-thermal-gc0.3/kT2e-6-seed$seed 0.3 1e-3 2e-6 $seed; done
for kT in 1e-5 3e-5 1e-4; do bud budding-thermal-gc0.3/kT$kT-seed1 0.3 1e-3 $kT 1; done
bud budding-thermal-gc0.3-tau5e-4/T0 0.3 5e-4 0 1
bud budding-thermal-gc0.3-tau5e-4/kT1e-5-seed1 0.3 5e-4 1e-5 1
/usr/bin/python3 "$here/analyze.py" flicker results/thermal-flicker --kT 0.05 --skip 0.03 --json "$json"
/usr/bin/python3 "$here/analyze.py" domains results/thermal-nucleation results/thermal-nucleation-T0 \
  results/thermal-nucleation-seed2 results/thermal-nucleation-m0.74 results/thermal-coarsening \
  results/thermal-coarsening-T0 --json "$json"
for d in budding-thermal budding-thermal-gc0.3 budding-thermal-gc0.3-tau5e-4; do
  /usr/bin/python3 "$here/analyze.py" budding results/$d/* --prefix $d/ --json "$json"
done
