// clothsim shaders --out DIR SCENE...: writes every shader source the GPU backend and the
// renderer can compile, assembled as they would be (no GL context), so that a second GLSL
// compiler can check them (scripts/check-shaders.sh). Not in the usage text: a tool for CI.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/cli.h"
#include "model/errors.h"
#include "scene/scene_loader.h"

#ifdef CLOTH_HAVE_RENDER
#include "gpu/shader_variants.h"
#endif

namespace cloth::app {
namespace {

constexpr const char* kHelp = R"(usage: clothsim shaders --out DIR SCENE...

Writes the compute kernels of every SCENE under every integrator and kernel variant to
DIR/<scene file name without .json>/*.comp, and the render shaders to DIR/render/*.vert and
*.frag, each assembled as the program would compile it (#version, #defines, resolved #includes).
)";

#ifdef CLOTH_HAVE_RENDER
void writeSource(const std::filesystem::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    if (!out.flush()) throw std::runtime_error("cannot write " + path.string());
}
#endif

}  // namespace

int shadersCommand(Args& args) {
    std::string outDir;
    std::vector<std::string> scenes;
    while (!args.done()) {
        if (!args.isFlag()) {
            scenes.push_back(args.next());
            continue;
        }
        const std::string f = args.flag();
        if (f == "--help") {
            std::fputs(kHelp, stdout);
            return kOk;
        }
        if (f == "--out") {
            outDir = args.value(f);
            continue;
        }
        args.unknown(f);
    }
    if (outDir.empty()) throw InputError("command line", "--out", "is required");
#ifdef CLOTH_HAVE_RENDER
    namespace fs = std::filesystem;
    const std::string dir = findShaderDirectory().path;
    std::size_t written = 0;
    const auto writeAll = [&](const fs::path& folder, const std::vector<ShaderVariant>& variants) {
        fs::create_directories(folder);
        for (const ShaderVariant& v : variants) writeSource(folder / v.name, v.source.text);
        written += variants.size();
    };
    for (const std::string& path : scenes)
        writeAll(fs::path(outDir) / fs::path(path).stem(),
                 computeShaderVariants(dir, loadScene(path)));
    writeAll(fs::path(outDir) / "render", renderShaderVariants(dir));
    std::printf("%zu shader sources from %s written to %s\n", written, dir.c_str(), outDir.c_str());
    return kOk;
#else
    (void)scenes;
    throw std::runtime_error("this clothsim was built without the GPU backend (CLOTH_GPU=OFF)");
#endif
}

}  // namespace cloth::app
