// Every source the GPU backend can hand the GLSL compiler for a scene, assembled without a GL
// context, so a second compiler (glslangValidator, scripts/check-shaders.sh) can check what
// Mesa alone would otherwise be the judge of.
#pragma once

#include <string>
#include <vector>

#include "gpu/shader_loader.h"
#include "model/scene.h"

namespace cloth {

// One assembled source and the file name it is written to: `name` is unique within one scene's
// variants and ends in the stage's extension (.comp, .vert, .frag).
struct ShaderVariant {
    std::string name;
    ShaderSource source;
};

// The compute kernels buildPrograms compiles for `scene` under every integrator (kernelsOf):
// with the forces pass global and tiled, with every collider static and every one dragged (the
// viewer), many_steps.comp for the Euler schemes (on a software rasteriser's and a hardware
// GPU's group size), all at the default 16x16 work group, and the forces pass also at the other
// work groups the tests build (8x8, 32x8, 5x3). Sources with identical text are listed once.
std::vector<ShaderVariant> computeShaderVariants(const std::string& dir, const Scene& scene);

// Every stage file of `dir`/render (.vert, .frag) as GlProgram assembles it: no defines.
std::vector<ShaderVariant> renderShaderVariants(const std::string& dir);

}  // namespace cloth
