#!/bin/sh
# The GPU sweeps of docs/performance.md ("GPU: work groups, shared-memory tiles, many steps per
# dispatch"), to repeat them on another device, e.g. a lent H100/H200:
#   bench/gpu_sweep.sh [CLOTHSIM] [OUT] [LABEL]
# (defaults build/clothsim, bench/results, the device kind you name, e.g. h100). Runs each sweep
# three times; compare best or median runs, and only with runs of the same device.
set -eu
exe=${1:-build/clothsim}
out=${2:-bench/results}
label=${3:-gpu}
for r in 1 2 3; do
    # Work-group shapes x where pass 1 reads the neighbours, with each pass timed alone.
    "$exe" bench speed --backend gpu --sizes 32,64,128,256,512,1024,2048,4096 \
        --workgroups 8x8,16x16,32x8,64x4,32x32 --gpu-forces both --gpu-dispatch per-step \
        --pass-times --out "$out" --label "${label}_workgroups_$r"
    # Many steps per dispatch against two dispatches per step: the crossover.
    "$exe" bench speed --backend gpu --sizes 8,12,16,20,24,32,48,64,96,128,256 \
        --gpu-dispatch per-step,many-steps --out "$out" --label "${label}_many_steps_$r"
    # How often the instability flag is read back.
    for every in 1 64 1024; do
        "$exe" bench speed --backend gpu --sizes 16,1024 --gpu-dispatch per-step,many-steps \
            --check-every "$every" --out "$out" --label "${label}_check_every_${every}_$r"
    done
done
