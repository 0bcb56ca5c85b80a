#!/usr/bin/env bash
# The checks that need a hardware GPU, in the order of what they decide, each cut at its own limit
# so that one device call (at most 600 s) runs them all
# (docs/performance.md, "On an NVIDIA H100/H200"):
#   1. the GPU tests of colliders, parity with the CPU, implicit Euler, multigrid, vbd and step
#      control (the colliders did not act on an H100 before their records went in with the
#      allocation);
#   2. the real-time frontier of vbd on the drape with the strain check: 10 sweeps (the largest N
#      whose sheet holds at 60 frames a second), then 1024² with 8 sweeps and 2 passes of the
#      levels (whether it holds at 60 frames a second), and what a step at 2048² costs;
#   3. the shipped real-time scene at 128²–1024² (its step's cost, whether it holds), and
#      bench/gpu_step_check.sh at 1024² (what the device's step check costs);
#   4. implicit Euler on the drape at 128² and 512², block-Jacobi and the multigrid V-cycle; 128²
#      multigrid with its line solves as one chain a line and in 32 chunks, to convergence and
#      capped at 1 iteration (what the per-step build costs, so that the difference gives the
#      cost of an iteration); the multigrid hierarchy's trace
#      (CLOTH_MULTIGRID_TRACE) of the stiff drape at 128², which NVIDIA stopped at iteration 0,
#      and at 33², which converged;
#   5. the rest of the GPU tests.
#   bench/gpu_checks.sh BUNDLE_DIR OUT_DIR [tests]
# With `tests`, only the GPU tests (1 and 5) run.
# BUNDLE_DIR is scripts/gpu-bench.sh's bundle with build/cloth_tests copied in. Everything lands in
# OUT_DIR/results.tgz (packed again after each check) and OUT_DIR/log.txt.
set -uo pipefail
dir=$(cd "${1:?bundle}" && pwd)
out=${2:?out}
only=${3:-all}
here=$(cd "$(dirname "$0")/.." && pwd)
res=$(mktemp -d)
mkdir -p "$out"
exec > >(tee -a "$out/log.txt") 2>&1
source "$here/scripts/gpu-bench.sh"  # use_bundle, device_label
set +e                                # each check runs under its own limit, whatever the last did
# One device call runs at most 600 s: each check's limit is cut to what is left before the
# deadline, keeping 80 s for the last tests, so that the script ends inside one call.
deadline=$((SECONDS + ${GPU_CHECKS_SECONDS:-540}))
limit() {  # limit N [KEEP]: N seconds, or what is left before the deadline less KEEP (at least 1)
    local left=$((deadline - SECONDS - ${2:-80}))
    if ((left < $1)); then echo $((left > 1 ? left : 1)); else echo "$1"; fi
}
use_bundle "$dir"
export CLOTH_REQUIRE_GPU=1
# The tests find scenes and shaders through the source path they were built with, and the
# bundle's test finds the executable in build/.
mkdir -p "$here/build" && [ -e "$here/build/clothsim" ] || cp "$dir/clothsim" "$here/build/"
src=$(strings "$dir/cloth_tests" | grep -m1 -o '^/[^ ]*/main$' || true)
[ -n "$src" ] && [ ! -e "$src" ] && mkdir -p "$(dirname "$src")" && ln -s "$here" "$src"
exe="$dir/clothsim"
pack() { tar czf "$out/results.tgz" -C "$res" . ; }
stamp() { echo "== $(date -u +%H:%M:%S) $*"; }

stamp info
nvidia-smi -L || true
"$exe" info | tee "$res/info.txt"
label=$(device_label < "$res/info.txt")
label=${label:-gpu}
pack

first='GpuCollider*:GpuCpuParity*:GpuImplicitSolve*:GpuMultigridSolve*:GpuIntegratorParity*:GpuStepControl*:GpuSelfCollision*'
stamp "tests: $first"
(cd "$here" && timeout "$(limit 110)" "$dir/cloth_tests" --gtest_filter="$first") \
    > "$res/gpu_tests_first_$label.log" 2>&1
echo "rc $?"; grep -E '^\[  (PASSED|FAILED) |tests? ran' "$res/gpu_tests_first_$label.log"
pack

if [ "$only" != tests ]; then
stamp "realtime vbd, 10 sweeps"
timeout "$(limit 120)" "$exe" bench realtime --backend gpu --no-error --methods vbd --out "$res" \
    --label "cotton_vbd10_strain_$label"
pack
# 1024² with 6 levels (the finest blocks 16 wide): on the CPU 10 sweeps and 8 sweeps with 2
# passes hold it at 1/240 s, 4 steps a frame; the bench halves 1/60 twice to get there.
stamp "realtime vbd at 1024, 8 sweeps, 2 passes"
timeout "$(limit 100)" "$exe" bench realtime --backend gpu --no-error --methods vbd --sizes 1024 \
    --out "$res" --set integrator.iterations=8 --set integrator.translation_level_passes=2 \
    --label "cotton_vbd8_passes2_1024_$label"
pack

# 2048² with 7 levels: on the CPU 8 sweeps with 2 passes hold it at 1/480 s, 8 steps a frame.
# What such a step costs here (predicted for the H200: 10.7-13.7 ms, docs/performance.md
# "vbd at 2048²").
stamp "vbd steps at 2048, 8 sweeps, 2 passes"
timeout "$(limit 40)" "$exe" run "$here/scenes/drape.json" --backend gpu --steps 48 \
    --set "cloth.resolution=[2048,2048]" \
    --set 'integrator={"method":"vbd","dt":0.00208333,"iterations":8,"translation_level_passes":2}' \
    2>&1 | tee "$res/vbd_steps_2048_$label.txt"
pack

# The shipped real-time scene (vbd, 20 sweeps, ρ = 0.9, 2 passes, friction) at larger sheets:
# what its step costs here, and whether the sheet holds (run checks max_strain every 0.1 s).
stamp "realtime scene"
for n in 128 256 512 1024 2048; do
    line=$(timeout "$(limit 15)" "$exe" run "$here/scenes/realtime.json" --backend gpu --steps 60 \
        --set "cloth.resolution=[$n,$n]" 2>&1 | grep -E 'ms/step|unstable|error' | tr '\n' ' ' ||
        echo "cut off at its limit")
    echo "$n: $line" | tee -a "$res/realtime_scene_$label.txt"
done
pack

stamp "step check 1024"
timeout "$(limit 70)" "$here/bench/gpu_step_check.sh" "$exe" "$res" "$label" 1024
pack

stamp "implicit Euler"
for n in 128 512; do
    for p in jacobi multigrid; do
        line=$(timeout "$(limit 20)" "$exe" run "$here/scenes/drape.json" --backend gpu \
            --set "cloth.resolution=[$n,$n]" \
            --set "integrator={\"method\":\"implicit_euler\",\"dt\":0.016667,\"preconditioner\":\"$p\",\"tolerance\":1e-6,\"max_iterations\":3000}" \
            --steps 10 --out-solves "$res/implicit_${label}_${n}_$p.csv" 2>&1 |
            grep -E 'ms/step|CG solves|unstable|error' | tr '\n' ' ' || echo "cut off at its limit")
        echo "$n $p: $line" | tee -a "$res/implicit_$label.txt"
    done
done
# The line solves in chunks (the default on hardware) against one chain a line, at 128², to
# convergence and capped at 1 iteration.
for chunks in 1 32; do
    for cap in 3000 1; do
        line=$(CLOTH_MULTIGRID_CHUNKS=$chunks timeout "$(limit 20)" "$exe" run "$here/scenes/drape.json" \
            --backend gpu --set "cloth.resolution=[128,128]" \
            --set "integrator={\"method\":\"implicit_euler\",\"dt\":0.016667,\"preconditioner\":\"multigrid\",\"tolerance\":1e-6,\"max_iterations\":$cap}" \
            --steps 10 2>&1 | grep -E 'ms/step|CG solves|error' | tr '\n' ' ' || echo "cut off at its limit")
        echo "128 multigrid, $chunks chunks, cap $cap: $line" | tee -a "$res/implicit_$label.txt"
    done
done
for n in 128 33; do
    CLOTH_MULTIGRID_TRACE=1 timeout "$(limit 20)" "$exe" run "$here/scenes/drape.json" --backend gpu \
        --set "cloth.resolution=[$n,$n]" --set material.stretch=1e6 \
        --set 'integrator={"method":"implicit_euler","dt":0.016667,"preconditioner":"multigrid","tolerance":1e-6,"max_iterations":3000}' \
        --steps 2 > "$res/multigrid_trace_${label}_${n}_1e6.txt" 2>&1
    cat "$res/multigrid_trace_${label}_${n}_1e6.txt"
done
pack
fi

stamp "tests: the rest"
(cd "$here" && timeout "$(limit 80 0)" "$dir/cloth_tests" --gtest_filter="Gpu*:-$first") \
    > "$res/gpu_tests_rest_$label.log" 2>&1
echo "rc $?"; grep -E '^\[  (PASSED|FAILED) |tests? ran' "$res/gpu_tests_rest_$label.log"
pack
stamp done
