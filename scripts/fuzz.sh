#!/usr/bin/env bash
# Fuzzes the scene loader with libFuzzer for SECONDS (default 60); exits non-zero on any finding
# (a crash, a sanitizer report, an exception other than InputError, a leak, a hang or an OOM).
# Needs clang-14 and libfuzzer-14-dev. Findings are left in build-fuzz/artifacts/.
set -euo pipefail

seconds="${1:-60}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$root/build-fuzz"
cxx="${CXX:-clang++-14}"

if ! command -v "$cxx" >/dev/null; then
    echo "fuzz.sh: $cxx not found (apt-get install clang-14 libfuzzer-14-dev)" >&2
    exit 1
fi

CXX="$cxx" cmake -S "$root" -B "$build" -DCLOTH_FUZZ=ON -DCLOTH_BUILD_TESTS=OFF \
    -DCLOTH_PYTHON=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" --target scene_loader_fuzz -j"$(nproc)"

# Seed with every shipped scene and every known-bad one; the corpus grows across runs.
rm -rf "$build/artifacts"  # findings of the latest run only
mkdir -p "$build/corpus" "$build/artifacts"
shopt -s nullglob
for seed in "$root"/scenes/*.json "$root"/tests/data/*.json "$root"/tests/data/bad_scenes/*; do
    cp -f "$seed" "$build/corpus/seed_$(basename "$seed")"
done
# The fuzz target reads NUL-separated --set overrides after the scene text.
good="$root/tests/data/good_scene.json"
{ cat "$good"; printf '\0integrator.dt=0.002\0colliders[1].radius=-1'; } >"$build/corpus/seed_set_1"
{ cat "$good"; printf '\0pins.0=[1,2]\0cloth.resolution=[3,3]\0wind=null'; } >"$build/corpus/seed_set_2"

# UBSan only reports by default; halting makes each report a finding libFuzzer saves.
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:${UBSAN_OPTIONS:-}"
export ASAN_OPTIONS="detect_stack_use_after_return=1:${ASAN_OPTIONS:-}"

status=0
"$build/scene_loader_fuzz" "$build/corpus" \
    -dict="$root/tests/fuzz/scene.dict" \
    -max_total_time="$seconds" -max_len=4096 -rss_limit_mb=2048 -timeout=10 \
    -artifact_prefix="$build/artifacts/" -print_final_stats=1 || status=$?

if [[ $status -ne 0 ]]; then
    echo "fuzz.sh: finding (libFuzzer exit $status); inputs in $build/artifacts/:" >&2
    ls -l "$build/artifacts/" >&2
    exit "$status"
fi
echo "fuzz.sh: no findings in ${seconds} s"
