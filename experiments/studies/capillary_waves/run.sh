#!/bin/sh
# Capillary waves of a straight phase boundary (README.md beside this script).
# 1. Two stripe runs of 6e4 and 5e4 steps (tau = 5e-6, the linearized scheme) with different
#    noise seeds and one bulk run of 2e4 steps (the same parameters in one phase), two at a time on
#    two cores (about an hour).
# 2. The time step and the scheme: 5e3 stripe steps and 2e3 bulk steps each at tau = 2e-5 with
#    the linearized scheme, and at 2e-5 and 5e-6 with the stabilized one (about 5 minutes).
# Then the analysis, which writes results.json here and docs/data/capillary_waves.json, and the
# figure docs/images/capillary_waves.png (figure.py).
# Usage: experiments/studies/capillary_waves/run.sh [build/membrane-flow]
set -e
exe=${1:-build/membrane-flow}
out=results/capillary_waves
here=$(dirname "$0")
run() { # name settings...
  name=$1
  shift
  HWLOC_COMPONENTS=-gl OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 nice "$exe" --quiet --overwrite "$@" \
    --set "Output/Directory=$out/$name" "$here/stripe.prm"
}
run stripe1 --set "Material/Noise seed=1" --set "Time stepping/Maximum steps=60000" &
{ run bulk --set "Initial phase/Type=uniform" --set "Material/Noise seed=2" --set "Time stepping/Maximum steps=20000"
  run stripe2 --set "Material/Noise seed=3" --set "Time stepping/Maximum steps=50000"; } &
wait
short() { # name scheme tau output-interval (5 tau)
  run "$1" --set "Cahn-Hilliard/Scheme=$2" --set "Time stepping/Time step=$3" --set "Output/Interval=$4" \
    --set "Time stepping/Maximum steps=5000"
  run "$1-bulk" --set "Cahn-Hilliard/Scheme=$2" --set "Time stepping/Time step=$3" --set "Output/Interval=$4" \
    --set "Time stepping/Maximum steps=2000" --set "Initial phase/Type=uniform" --set "Material/Noise seed=2"
}
short linearized-2e-5 linearized 2e-5 1e-4 &
{ short stabilized-2e-5 stabilized 2e-5 1e-4; short stabilized-5e-6 stabilized 5e-6 2.5e-5; } &
wait
analyze() { # json stripes... (the bulk run follows --bulk)
  json=$1
  shift
  PYTHONPATH=python /usr/bin/python3 -m membrane_flow capillary "$@" --json "$out/$json.json"
}
analyze main "$out/stripe1" "$out/stripe2" --bulk "$out/bulk"
for case in linearized-2e-5 stabilized-2e-5 stabilized-5e-6; do
  analyze "$case" "$out/$case" --bulk "$out/$case-bulk" --skip 0.004 --modes 4 --batches 10
done
/usr/bin/python3 - "$out" "$here/results.json" <<'PY'
import json, os, sys
out, target = sys.argv[1:]
result = json.load(open(os.path.join(out, 'main.json')))
result['scheme_comparison'] = {case: json.load(open(os.path.join(out, case + '.json')))
                               for case in ('linearized-2e-5', 'stabilized-2e-5', 'stabilized-5e-6')}
with open(target + '.part', 'w') as f:
    json.dump(result, f, indent=1)
os.replace(target + '.part', target)
PY
cp "$here/results.json" docs/data/capillary_waves.json
/usr/bin/python3 "$here/figure.py"
