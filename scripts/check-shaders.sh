#!/usr/bin/env bash
# Checks every shader source clothsim can compile with glslangValidator, the Khronos reference
# GLSL compiler: Mesa accepts what stricter drivers refuse. `clothsim shaders` writes them
# assembled as the program compiles them (#version, the scene's #defines, resolved #includes):
# the compute kernels of every shipped and test scene under every integrator and kernel variant,
# and the render shaders. Usage: check-shaders.sh [CLOTHSIM]; needs glslang-tools.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
exe="${1:-$root/build/clothsim}"
out="$(cd "$(dirname "$exe")" && pwd)/shader-check"

if ! command -v glslangValidator >/dev/null; then
    echo "check-shaders.sh: glslangValidator not found (apt-get install glslang-tools)" >&2
    exit 1
fi

rm -rf "$out"
# The source tree's shaders, not the copy next to the executable.
CLOTH_SHADER_DIR="$root/shaders" "$exe" shaders --out "$out" \
    "$root"/scenes/*.json "$root"/tests/data/*.json

# OpenGL GLSL as written (no -V: that would check it as Vulkan SPIR-V input): each file's own
# #version, the stage from its extension. glslangValidator prints each file's name and its
# messages (a message's line N:L is file N of the source's #line directives, line L mod 10000);
# only files with a message are shown.
log="$out/glslang.log"
status=0
find "$out" -type f \( -name '*.comp' -o -name '*.vert' -o -name '*.frag' \) -print0 | sort -z |
    xargs -0 -n 100 glslangValidator >"$log" 2>&1 || status=$?
# A render program's stages are also linked (-l), which checks that what the vertex stage writes
# matches what the fragment stage reads: X.vert with X.frag where both exist.
for vert in "$out"/render/*.vert; do
    frag="${vert%.vert}.frag"
    if [[ -f "$frag" ]]; then
        glslangValidator -l "$vert" "$frag" >>"$log" 2>&1 || status=$?
    fi
done
count=$(find "$out" -type f \( -name '*.comp' -o -name '*.vert' -o -name '*.frag' \) | wc -l)
if [[ $status -ne 0 ]] || grep -q -E 'ERROR|WARNING' "$log"; then
    awk '/^\// { file = $0; next } NF { if (file) print file; file = ""; print }' "$log" >&2
    echo "check-shaders.sh: glslangValidator found problems in the shaders above (sources in $out)" >&2
    exit 1
fi
echo "check-shaders.sh: $count shader sources pass glslangValidator"
