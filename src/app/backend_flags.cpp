#include "app/backend_flags.h"

#include <cstdio>
#include <cstdlib>
#include <regex>

#include "model/errors.h"

namespace cloth::app {

bool parseBackendFlag(const std::string& flag, Args& args, BackendChoice& choice) {
    if (flag == "--backend")
        parseBackend(flag, args.value(flag), choice);
    else if (flag == "--precision")
        choice.precision = parsePrecision(flag, args.value(flag));
    else if (flag == "--threads")
        choice.threads = int(args.positiveInt(flag));
    else
        return false;
    return true;
}

void refuseGpuDouble(const BackendChoice& choice, bool precisionGiven) {
    if (!choice.automatic && choice.backend == Backend::Gpu && precisionGiven &&
        choice.precision == Precision::Double)
        throw InputError("command line", "--precision",
                         "the GPU backend computes in float; --precision double needs --backend "
                         "cpu (or leave --precision out)");
}

bool RunFlags::take(const std::string& flag, Args& args) {
    precisionGiven |= flag == "--precision";
    if (parseBackendFlag(flag, args, backend)) return true;
    if (flag != "--set") return false;
    addSet(sets, args.value(flag));
    return true;
}

void settleBackendAndSay(BackendChoice& choice, const Scene& scene, bool doubleAsked, bool quiet) {
    const std::string line = settleBackend(choice, scene, doubleAsked);
    if (!quiet && !line.empty()) std::fprintf(stderr, "clothsim: %s\n", line.c_str());
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
    if (const char* dir = environment("CLOTH_SHADER_DIR")) setup.shaderDir = dir;
    if (const char* device = environment("CLOTH_EGL_DEVICE")) {
        char* end = nullptr;
        const long index = std::strtol(device, &end, 10);
        if (*end != '\0' || index < 0 || index > 1000)
            throw InputError("", "CLOTH_EGL_DEVICE",
                             std::string("'") + device + "' is not a device index");
        setup.eglDevice = int(index);
    }
    return setup;
}

std::string benchDirFromEnvironment() {
    const char* dir = environment("CLOTH_BENCH_DIR");
    return dir != nullptr ? dir : "";
}

}  // namespace cloth::app
