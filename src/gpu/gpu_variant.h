// Which kernel a scene compiles to (DESIGN.md §3): the #defines, the work-group size and the
// checks that the grid fits the device. No GL here, so `validate` and tests can use it freely.
#pragma once

#include <string>

#include "core/scene.h"
#include "gpu/shader_loader.h"

namespace cloth {

struct GpuInfo;

struct WorkGroup {
    int x = 16, y = 16;
};

// The work-group size to compile with: CLOTH_WORKGROUP=WXxWY if set, else `requested`. Throws
// InputError naming CLOTH_WORKGROUP (or the option) when malformed or beyond `info`'s limits;
// with `info` null only the syntax and positivity are checked.
WorkGroup chooseWorkGroup(WorkGroup requested, const GpuInfo* info);

// Throws InputError (key cloth.resolution) when the grid needs more than the device allows:
// over min(65535, device limit) work groups along a dimension, or vertex buffers larger than
// one SSBO binding may be.
void checkGridFits(const Scene& scene, WorkGroup wg, const GpuInfo& info);

// The scene's kernel variant: HAS_STRUCTURAL/HAS_SHEAR/HAS_BEND, HAS_WIND, NUM_PLANES,
// NUM_SPHERES, the integrator, WX/WY, and the generated spring table and collider order. A
// feature the scene lacks is absent, not multiplied by zero. Pins and the grab are not
// features: the viewer changes them at run time, so their (one-compare) code is always there.
Defines gpuDefines(const Scene& scene, WorkGroup wg);

// The assembled source of compute/forces.comp or compute/integrate.comp for `scene`.
ShaderSource assembleKernel(const std::string& dir, const std::string& file, const Scene& scene,
                            WorkGroup wg);

}  // namespace cloth
