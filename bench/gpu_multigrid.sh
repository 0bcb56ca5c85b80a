#!/bin/sh
# implicit_euler's preconditioners on the GPU (docs/performance.md, "Multigrid on the GPU"): the
# drape at Δt = 1/60, relative residual 1e-6, cap 3000 iterations, block-Jacobi against the
# multigrid V-cycle, cotton and a membrane of 1e6 N/m; each run's summary line (wall ms per step,
# iterations per step) and its per-step CSV (--out-solves).
#   bench/gpu_multigrid.sh [CLOTHSIM] [OUT] [LABEL] [SIZES]
# (defaults build/clothsim, bench/results, gpu, "128 256 512 1024"). Each run is cut at 30 s.
set -eu
exe=${1:-build/clothsim}
out=${2:-bench/results}
label=${3:-gpu}
sizes=${4:-128 256 512 1024}
here=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
summary="$out/multigrid_$label.txt"
: > "$summary"
for n in $sizes; do
    for stretch in cotton 1e6; do
        steps=30
        set --
        [ "$stretch" = 1e6 ] && { steps=10; set -- --set material.stretch=1e6; }
        for p in jacobi multigrid; do
            csv="$out/multigrid_${label}_${n}_${stretch}_$p.csv"
            line=$(timeout 30 "$exe" run "$here/scenes/drape.json" --backend gpu \
                --set "cloth.resolution=[$n,$n]" --set 'integrator.method="implicit_euler"' \
                --set integrator.dt=0.016667 --set "integrator.preconditioner=\"$p\"" \
                --set integrator.tolerance=1e-6 --set integrator.max_iterations=3000 "$@" \
                --steps "$steps" --out-solves "$csv" 2>&1 | grep -E 'ms/step|CG solves' |
                tr '\n' ' ' || echo "cut off at 30 s")
            echo "$n $stretch $steps $p: $line" | tee -a "$summary"
        done
    done
done
