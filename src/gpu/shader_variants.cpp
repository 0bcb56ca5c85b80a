#include "gpu/shader_variants.h"

#include <algorithm>
#include <filesystem>
#include <set>

#include "gpu/gpu_variant.h"

namespace cloth {
namespace {

// "compute/forces.comp" -> "forces"
std::string stem(const std::string& file) {
    return std::filesystem::path(file).stem().string();
}

}  // namespace

std::vector<ShaderVariant> computeShaderVariants(const std::string& dir, const Scene& scene) {
    std::vector<ShaderVariant> variants;
    std::set<std::string> texts;
    const auto add = [&](const std::string& name, const std::string& file, const Scene& s,
                         WorkGroup wg, const Defines& extra, const std::vector<bool>& dragged) {
        ShaderSource source = assembleKernel(dir, file, s, wg, extra, dragged);
        if (texts.insert(source.text).second) variants.push_back({name, std::move(source)});
    };
    std::vector<std::vector<bool>> dragSets = {{}};
    if (!scene.colliders.empty())
        dragSets.push_back(std::vector<bool>(scene.colliders.size(), true));
    // The group sizes manyStepsGroupSize picks: a software rasteriser's, and a hardware GPU's.
    const int manyStepsGroups[] = {32, 1024};
    for (Method method : kMethods) {
        Scene s = scene;
        s.integrator.method = method;
        for (std::size_t d = 0; d < dragSets.size(); ++d) {
            const std::string drag = d == 0 ? "" : ".dragged";
            for (bool tiled : {false, true}) {
                Defines extra;
                if (tiled) extra.push_back({"FORCES_TILED", ""});
                const std::string prefix =
                    std::string(methodName(method)) + drag + (tiled ? ".tiled" : "");
                for (Kernel k : kernelsOf(method, Preconditioner::Jacobi, !s.colliders.empty()))
                    add(prefix + "." + stem(kernelFile(k)) + ".comp", kernelFile(k), s, {}, extra,
                        dragSets[d]);
                if (method == kMethods[0] && d == 0 && !tiled)  // any integrator's: once
                    add("step_check.comp", kernelFile(Kernel::StepCheck), s, {}, {}, {});
                if (s.selfCollision)  // the same for every integrator: once per drag set
                    for (Kernel k : selfCollisionKernels())
                        add(std::string(drag.empty() ? "" : "dragged.") + stem(kernelFile(k)) +
                                ".comp",
                            kernelFile(k), s, {}, {}, dragSets[d]);
                if (method == Method::ImplicitEuler) {  // the preconditioners' variants
                    for (Preconditioner p : {Preconditioner::Jacobi, Preconditioner::Multigrid}) {
                        Scene preconditioned = s;
                        preconditioned.integrator.preconditioner = p;
                        // The multigrid's line solves: one chain a line, or the most chunks.
                        for (int chunks : {1, kMultigridChunks}) {
                            if (p != Preconditioner::Multigrid && chunks > 1) continue;
                            Defines defines = extra;
                            std::string name = prefix + "." + preconditionerName(p);
                            if (p == Preconditioner::Multigrid) {
                                for (const auto& define : multigridChunkDefines(chunks))
                                    defines.push_back(define);
                                name += ".chunks" + std::to_string(chunks);
                            }
                            for (Kernel k : kernelsOf(method, p, !s.colliders.empty()))
                                add(name + "." + stem(kernelFile(k)) + ".comp", kernelFile(k),
                                    preconditioned, {}, defines, dragSets[d]);
                        }
                    }
                }
                if (method == Method::ExplicitEuler || method == Method::SymplecticEuler) {
                    for (int group : manyStepsGroups) {
                        Defines many = extra;
                        many.push_back({"MANY_STEPS_GROUP", std::to_string(group)});
                        add(prefix + ".many" + std::to_string(group) + ".many_steps.comp",
                            kernelFile(Kernel::ManySteps), s, {}, many, dragSets[d]);
                    }
                }
            }
        }
        for (WorkGroup wg : {WorkGroup{8, 8}, WorkGroup{32, 8}, WorkGroup{5, 3}})
            for (bool tiled : {false, true}) {
                Defines extra;
                if (tiled) extra.push_back({"FORCES_TILED", ""});
                add(std::string(methodName(method)) + (tiled ? ".tiled" : "") + ".wg" +
                        std::to_string(wg.x) + "x" + std::to_string(wg.y) + ".forces.comp",
                    kernelFile(Kernel::Forces), s, wg, extra, {});
            }
    }
    return variants;
}

std::vector<ShaderVariant> renderShaderVariants(const std::string& dir) {
    namespace fs = std::filesystem;
    std::vector<std::string> files;
    for (const fs::directory_entry& e : fs::directory_iterator(fs::path(dir) / "render")) {
        const std::string ext = e.path().extension().string();
        if (e.is_regular_file() && (ext == ".vert" || ext == ".frag"))
            files.push_back("render/" + e.path().filename().string());
    }
    std::sort(files.begin(), files.end());
    std::vector<ShaderVariant> variants;
    for (const std::string& file : files)
        variants.push_back({fs::path(file).filename().string(), assembleShader(dir, file, {})});
    return variants;
}

}  // namespace cloth
