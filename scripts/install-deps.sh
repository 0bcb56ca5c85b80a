#!/usr/bin/env bash
# Installs the Debian packages clothsim needs, only those missing; non-interactive, through sudo
# when not root. Nothing is vendored: every dependency is a Debian package.
set -euo pipefail

PACKAGES=(
    cmake make g++ pkg-config                 # build (g++ brings libasan, libubsan, libtsan)
    nlohmann-json3-dev libglm-dev             # scene files, vector maths
    libtinyobjloader-dev                      # mesh colliders (OBJ)
    libgtest-dev libgmock-dev                 # tests
    libegl-dev libgl-dev libglew-dev          # GPU backend: headless EGL + OpenGL 4.3 compute
    libegl-mesa0 libgl1-mesa-dri              # Mesa (llvmpipe where there is no GPU)
    mesa-vulkan-drivers                       # lavapipe, under zink: the GPU tests' second GL
    libglfw3-dev libimgui-dev libstb-dev      # viewer window, its panel, PNG output
    xvfb xauth xdotool                        # viewer tests without a display, real X input
    clang-14 libfuzzer-14-dev                 # the scene-loader fuzzer
    glslang-tools                             # shaders checked by a second compiler
    gnuplot-nox                               # bench accuracy/stability plots (PNG, SVG)
    libbullet-dev                             # bench speed --peer bullet (btSoftBody)
    python3-dev pybind11-dev                  # the Python module (python/), for Debian's python3
    python3-numpy python3-pytest              # its arrays and its tests (tests/python/)
    python3-matplotlib                        # examples/sweep.py's plot
)

missing=()
for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
    exit 0
fi

echo "installing Debian packages: ${missing[*]}"
sudo=()
if [ "$(id -u)" -ne 0 ]; then
    sudo=(sudo)
fi
"${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
"${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    "${missing[@]}"
