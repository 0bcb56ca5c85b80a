#!/usr/bin/env bash
# The GPU benchmarks on a machine with a hardware GPU, headless through EGL (no display, no window
# system, no root). Two steps:
#
#   scripts/gpu-bench.sh bundle [BUILD_DIR] [BUNDLE_DIR]
#       here, on the build machine: copies BUILD_DIR/clothsim (a Release build; default build/),
#       the shared libraries it loads (all but the C library's, which the target provides) and
#       the shaders into BUNDLE_DIR (default build-bundle/), for a target whose glibc is at least
#       the build machine's. The GL loaders travel too (libEGL, libOpenGL from glvnd): the target
#       needs only its GPU driver.
#
#   scripts/gpu-bench.sh run BUNDLE_DIR [OUT_DIR] [--quick]
#       on the target: `clothsim info`, then `bench speed` (bench/hanging_per_vertex.json, GPU,
#       32² … 4096², with each pass timed alone) and `bench realtime` (every integrator, GPU, no
#       reference runs: those are CPU work), each file labelled with the device, into OUT_DIR
#       (default bench/results). --quick: a few sizes only, to check the set-up.
#
# A build directory that is not a bundle also runs (`run build`) where its libraries are installed.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)

usage() {
    sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//' >&2
    exit 2
}

bundle() {
    local build=${1:-build} dest=${2:-build-bundle}
    [ -x "$build/clothsim" ] || { echo "gpu-bench: $build/clothsim: no such executable" >&2; exit 2; }
    grep -q 'CMAKE_BUILD_TYPE:STRING=Release' "$build/CMakeCache.txt" 2>/dev/null ||
        echo "gpu-bench: warning: $build is not a Release build; bench refuses Debug timings" >&2
    rm -rf "$dest"
    mkdir -p "$dest/lib"
    cp "$build/clothsim" "$dest/"
    cp -r "$here/shaders" "$dest/shaders"
    # Everything ldd resolves except the C library's own objects (they must be the target's).
    ldd "$build/clothsim" | awk '/=> \// { print $3 }' | while read -r lib; do
        case "$(basename "$lib")" in
            libc.so.*|libm.so.*|libdl.so.*|libpthread.so.*|librt.so.*|ld-linux*) ;;
            *) cp -L "$lib" "$dest/lib/" ;;
        esac
    done
    echo "gpu-bench: bundled $build/clothsim with $(ls "$dest/lib" | wc -l) libraries in $dest ($(du -sh "$dest" | cut -f1))"
}

# A file-name label from the GL renderer string, e.g. "NVIDIA H100 80GB HBM3/PCIe/SSE2" → nvidia_h100_80gb_hbm3.
device_label() {
    sed -n "s/.*GL renderer: *//p" | head -1 | sed "s| (.*||; s|/.*||" | tr 'A-Z' 'a-z' | tr -c 'a-z0-9\n' '_' |
        sed 's/__*/_/g; s/^_//; s/_$//'
}

# The environment that runs a bundle's executable (or a build's, where it has no lib/ or shaders/).
use_bundle() {
    local dir=$1
    [ -d "$dir/lib" ] && export LD_LIBRARY_PATH="$dir/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
    [ -d "$dir/shaders" ] && export CLOTH_SHADER_DIR="$dir/shaders"
    # glvnd finds NVIDIA's EGL through a vendor file; container images keep it beside the driver.
    if [ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" ]; then
        for f in /usr/share/glvnd/egl_vendor.d/10_nvidia.json \
                 /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json; do
            [ -f "$f" ] && { export __EGL_VENDOR_LIBRARY_FILENAMES=$f; break; }
        done
    fi
    return 0
}

run() {
    local dir=${1:?}; shift
    local out=bench/results quick=0
    for a in "$@"; do
        case "$a" in
            --quick) quick=1 ;;
            -*) usage ;;
            *) out=$a ;;
        esac
    done
    local exe="$dir/clothsim"
    [ -x "$exe" ] || { echo "gpu-bench: $exe: no such executable" >&2; exit 2; }
    use_bundle "$dir"
    mkdir -p "$out"
    local info
    info=$("$exe" info)
    echo "$info"
    local label
    label=$(echo "$info" | device_label)
    [ -n "$label" ] || { echo "gpu-bench: clothsim info names no GL renderer" >&2; exit 1; }
    case "$label" in
        llvmpipe*|softpipe*|swrast*) echo "gpu-bench: warning: $label is a software rasterizer" >&2 ;;
    esac
    echo "$info" > "$out/gpu_info_$label.txt"
    local sizes=32,64,128,256,512,1024,2048,4096 rt=()
    [ $quick = 1 ] && { sizes=64,1024; rt=(--quick --sizes 64,256); }
    echo "== bench speed ($label)"
    "$exe" bench speed "$here/bench/hanging_per_vertex.json" --backend gpu --sizes "$sizes" \
        --pass-times --out "$out" --label "hanging_per_vertex_$label"
    echo "== bench realtime ($label)"
    "$exe" bench realtime --backend gpu --no-error --max-size 4096 "${rt[@]}" \
        --out "$out" --label "cotton_$label"
}

# Sourced (bench/gpu_checks.sh), it only defines the functions above.
[ "${BASH_SOURCE[0]}" = "$0" ] || return 0
case "${1:-}" in
    bundle) shift; bundle "$@" ;;
    run) shift; run "$@" ;;
    *) usage ;;
esac
