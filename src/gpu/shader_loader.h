// Compute shader sources (DESIGN.md §3): GLSL has no #include, so the loader resolves
// `#include "x.glsl"` itself, prepends `#version` and the scene's #defines, and maps the
// compiler's file numbers back to file names in error logs.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace cloth {

// Where the shaders are: gpuSetup().shaderDir (the app's CLOTH_SHADER_DIR), else shaders/ next to
// the executable, else the source tree's shaders/ (CLOTH_SOURCE_SHADER_DIR). `how` says which,
// for error messages.
struct ShaderDirectory {
    std::string path;
    std::string how;
};
ShaderDirectory findShaderDirectory();

// Macros prepended to every shader, in order: {"HAS_SHEAR", ""}, {"NUM_PLANES", "1"}.
using Defines = std::vector<std::pair<std::string, std::string>>;

// One compilable source. `files[n]` is the file behind GLSL source-string number n (the second
// argument of the `#line` directives the loader writes); files[0] is the prepended header.
struct ShaderSource {
    std::string name;  // the top-level file, e.g. "compute/forces.comp"
    std::string text;
    std::vector<std::string> files;
};

// Reads `dir`/`file`, resolving includes relative to the including file (each file once) and
// evaluating #ifdef/#ifndef/#else/#endif against `defines` and the file's own #defines, so code
// for a feature the scene lacks is not in the text at all (DESIGN.md §3). Other #if lines go to
// the GLSL compiler. Blank lines keep the line numbers. Throws std::runtime_error (missing file,
// include cycle, unbalanced conditional) naming file and line.
ShaderSource assembleShader(const std::string& dir, const std::string& file, const Defines& defines,
                            int glslVersion = 430);

// Rewrites "N:LINE(COL): error" (Mesa), "N(LINE) : error" (NVIDIA) and "ERROR: N:LINE:" lines of
// a compiler log into "file:LINE..." using `files`.
std::string mapShaderLog(const std::string& log, const std::vector<std::string>& files);

// The shader storage blocks the assembled source declares (`layout(std430, ...) buffer Name {`):
// what the kernel needs of GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS. The loader has already removed
// the blocks of features the scene lacks, so this is what the driver counts as active.
int storageBlockCount(const ShaderSource& source);

// Throws GpuUnavailable (exit 4) before compiling when the kernel declares more storage blocks
// than the device allows one compute shader (`limit`; GL guarantees 8): naming the kernel, both
// numbers and what to do instead, rather than a link error.
void checkStorageBlocks(const ShaderSource& source, int limit);

// Compiles and links one compute program; needs a current GL context. Throws std::runtime_error
// with the mapped log.
unsigned compileComputeProgram(const ShaderSource& source);

}  // namespace cloth
