#!/bin/sh
# What the step control's check costs on the GPU (docs/performance.md, "Step control: what the
# check costs"): the drape in cotton, vbd 20 sweeps with Chebyshev ρ 0.9 at Δt = 1/60, without
# the key, with a limit no step reaches (10: the check alone) and with 0.1, alternated three times;
# each run's summary (wall, GPU ms per step, the steps split).
#   bench/gpu_step_check.sh [CLOTHSIM] [OUT] [LABEL] [SIZES]
# (defaults build/clothsim, bench/results, gpu, "256 512 1024"). Each run is cut at 60 s.
set -eu
exe=${1:-build/clothsim}
out=${2:-bench/results}
label=${3:-gpu}
sizes=${4:-256 512 1024}
here=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
summary="$out/step_check_$label.txt"
: > "$summary"
for n in $sizes; do
    for r in 1 2 3; do
        for limit in none 10 0.1; do
            set --
            [ "$limit" != none ] && set -- --set "integrator.max_step_strain=$limit"
            line=$(timeout 60 "$exe" run "$here/scenes/drape.json" --backend gpu \
                --set "cloth.resolution=[$n,$n]" --set max_strain=100 \
                --set 'integrator={"method":"vbd","dt":0.016667,"iterations":20,"chebyshev_rho":0.9}' \
                "$@" --steps 120 2>&1 | grep -E 'wall|ms/step|step control' | tr '\n' ' ' ||
                echo "cut off at 60 s")
            echo "$n run $r, max_step_strain $limit: $line" | tee -a "$summary"
        done
    done
done
