#include "app/backend_options.h"

#include <cstdlib>
#include <filesystem>
#include <regex>

#include "model/errors.h"

namespace cloth::app {

void refuseGpuDouble(const BackendChoice& choice, bool precisionGiven) {
    if (!choice.automatic && choice.backend == Backend::Gpu && precisionGiven &&
        choice.precision == Precision::Double)
        throw InputError("command line", "--precision",
                         "the GPU backend computes in float; --precision double needs --backend "
                         "cpu (or leave --precision out)");
}

void parseBackend(const std::string& flag, const std::string& value, BackendChoice& choice) {
    choice.automatic = value == "auto";
    if (value == "cpu" || value == "gpu")
        choice.backend = value == "gpu" ? Backend::Gpu : Backend::Cpu;
    else if (!choice.automatic)
        throw InputError("command line", flag, "expected cpu, gpu or auto, got '" + value + "'");
}

Precision parsePrecision(const std::string& flag, const std::string& value) {
    if (value == "float") return Precision::Float;
    if (value == "double") return Precision::Double;
    throw InputError("command line", flag, "expected float or double, got '" + value + "'");
}

namespace {

// The variable's value, or nullptr when it is unset or empty.
const char* environment(const char* name) {
    const char* value = std::getenv(name);
    return value != nullptr && *value != '\0' ? value : nullptr;
}

}  // namespace

BackendChoice backendChoiceFromEnvironment() {
    BackendChoice choice;
    if (const char* isa = environment("CLOTH_CPU_ISA")) {
        const auto named = cpuIsaFromName(isa);
        if (!named)
            throw InputError(
                "", "CLOTH_CPU_ISA",
                std::string("expected scalar, generic, avx2 or avx512, got '") + isa + "'");
        choice.isa = *named;
    }
    if (const char* wg = environment("CLOTH_WORKGROUP")) {
        static const std::regex re(R"(^\s*(\d{1,6})\s*[xX]\s*(\d{1,6})\s*$)");
        std::cmatch m;
        if (!std::regex_match(wg, m, re))
            throw InputError("", "CLOTH_WORKGROUP",
                             std::string("'") + wg + "' is not of the form WXxWY, e.g. 16x16");
        choice.gpu.workGroupX = std::stoi(m[1].str());
        choice.gpu.workGroupY = std::stoi(m[2].str());
        choice.gpu.workGroupKey = "CLOTH_WORKGROUP";
    }
    return choice;
}

GpuSetup gpuSetupFromEnvironment() {
    GpuSetup setup;
    if (const char* dir = environment("CLOTH_SHADER_DIR")) {
        std::error_code ec;
        if (!std::filesystem::is_directory(dir, ec))
            throw InputError(
                "", "CLOTH_SHADER_DIR",
                std::string("'") + dir + "' is not a directory (the project's shaders/)");
        setup.shaderDir = dir;
    }
    if (const char* device = environment("CLOTH_EGL_DEVICE")) {
        char* end = nullptr;
        const long index = std::strtol(device, &end, 10);
        if (*end != '\0' || index < 0 || index > 1000)
            throw InputError("", "CLOTH_EGL_DEVICE",
                             std::string("'") + device + "' is not a device index");
        setup.eglDevice = int(index);
    }
    if (const char* trace = environment("CLOTH_MULTIGRID_TRACE")) {
        if (std::string(trace) != "0" && std::string(trace) != "1")
            throw InputError("", "CLOTH_MULTIGRID_TRACE",
                             std::string("expected 0 or 1, got '") + trace + "'");
        setup.traceMultigrid = std::string(trace) == "1";
    }
    if (const char* chunks = environment("CLOTH_MULTIGRID_CHUNKS")) {
        char* end = nullptr;
        const long count = std::strtol(chunks, &end, 10);
        if (end == chunks || *end != '\0' ||
            !(count == 1 || (count >= 8 && count <= kMultigridChunks)))
            throw InputError("", "CLOTH_MULTIGRID_CHUNKS",
                             std::string("expected 1 or 8 to ") + std::to_string(kMultigridChunks) +
                                 ", got '" + chunks + "'");
        setup.multigridChunks = int(count);
    }
    return setup;
}

std::string benchDirFromEnvironment() {
    const char* dir = environment("CLOTH_BENCH_DIR");
    return dir != nullptr ? dir : "";
}

}  // namespace cloth::app
