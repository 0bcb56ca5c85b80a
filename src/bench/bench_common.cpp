#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "bench/bench.h"
#include "model/errors.h"
#include "model/output_file.h"
#include "scene/scene_loader.h"

extern char** environ;

namespace cloth::app {

namespace fs = std::filesystem;

std::string BenchTarget::id() const {
    return std::string(backendName(backend)) + "_" + precisionName(precision);
}

std::vector<Method> parseMethods(const std::string& flag, const std::string& value) {
    if (value == "all") return {std::begin(kMethods), std::end(kMethods)};
    std::vector<Method> methods;
    std::stringstream in(value);
    for (std::string name; std::getline(in, name, ',');) {
        const auto m = methodFromName(name);
        if (!m)
            throw InputError(
                "command line", flag,
                "unknown integrator '" + name + "'; expected all or a list of " + methodList());
        methods.push_back(*m);
    }
    if (methods.empty() || value.back() == ',')
        throw InputError(
            "command line", flag,
            "expected all or a comma-separated list of " + methodList() + ", got '" + value + "'");
    return methods;
}

double parsePositive(const std::string& flag, const std::string& value) {
    char* end = nullptr;
    errno = 0;
    const double x = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(x) || x <= 0)
        throw InputError("command line", flag, "expected a positive number, got '" + value + "'");
    return x;
}

std::vector<double> parsePositiveList(const std::string& flag, const std::string& value) {
    std::vector<double> list;
    std::stringstream in(value);
    for (std::string item; std::getline(in, item, ',');) list.push_back(parsePositive(flag, item));
    if (list.empty() || value.back() == ',')
        throw InputError(
            "command line", flag,
            "expected a comma-separated list of positive numbers, got '" + value + "'");
    return list;
}

std::vector<BenchTarget> parseTargets(const std::string& flag, const std::string& value,
                                      const std::vector<Precision>& cpuPrecisions) {
    if (value != "cpu" && value != "gpu" && value != "both")
        throw InputError("command line", flag, "expected cpu, gpu or both, got '" + value + "'");
    std::vector<BenchTarget> targets;
    if (value != "gpu")
        for (Precision p : cpuPrecisions) targets.push_back({Backend::Cpu, p});
    if (value != "cpu") targets.push_back({Backend::Gpu, Precision::Float});
    return targets;
}

BackendChoice choiceFor(const BenchTarget& target, const BackendChoice& base) {
    BackendChoice c = base;
    c.backend = target.backend;
    c.precision = target.precision;
    return c;
}

bool runsMethod(const BenchTarget& target, const Scene& scene, Method method,
                const BackendChoice& base) {
    if (target.backend != Backend::Gpu) return true;
    Scene s = scene;
    s.integrator.method = method;
    try {
        makeSolver(s, choiceFor(target, base));
    } catch (const InputError& e) {
        std::fprintf(stderr, "clothsim bench: skipping %s on %s: %s\n", methodName(method),
                     target.id().c_str(), e.what());
        return false;
    }
    return true;
}

bool MethodSupport::runs(const BenchTarget& target, const Scene& scene, Method method,
                         const BackendChoice& base) {
    const auto key = std::make_pair(target.id(), method);
    const auto it = known_.find(key);
    if (it != known_.end()) return it->second;
    return known_[key] = runsMethod(target, scene, method, base);
}

std::vector<BenchTarget> availableTargets(std::vector<BenchTarget> targets, const Scene& scene,
                                          bool gpuOnly, const BackendChoice& base) {
    std::vector<BenchTarget> kept;
    for (const BenchTarget& t : targets) {
        if (t.backend == Backend::Gpu && !gpuOnly) {
            try {
                makeSolver(scene, choiceFor(t, base));
            } catch (const GpuUnavailable& e) {
                std::fprintf(stderr, "clothsim bench: skipping the GPU (unavailable: %s)\n",
                             e.what());
                continue;
            }
        }
        kept.push_back(t);
    }
    return kept;
}

Scene loadBenchScene(BenchCommonOptions& o) {
    Scene scene = loadScene(o.scenePath, o.sets);
    if (o.label.empty()) o.label = scene.name;
    checkOutputs(o.out, o.label);
    return scene;
}

void checkOutputs(const std::string& dir, const std::string& label) {
    if (!isFileNamePart(label))
        throw InputError(
            "command line", "--label",
            "names files in --out: expected a non-empty name of at most 200 bytes "
            "without '/', '\\' or control characters, got " +
                (label.size() > 200 ? std::to_string(label.size()) + " bytes" : "'" + label + "'"));
    outputPath(dir, "");
}

std::string outputPath(const std::string& dir, const std::string& name) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (!fs::is_directory(dir, ec) || access(dir.c_str(), W_OK) != 0)
        throw InputError("command line", "--out", "cannot write into directory '" + dir + "'");
    return (fs::path(dir) / name).string();
}

std::string cell(double value) {
    if (!std::isfinite(value)) return "";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", value);
    return buf;
}

std::string join(const std::vector<std::string>& items, char separator) {
    std::string s;
    for (const std::string& item : items) {
        if (!s.empty()) s += separator;
        s += item;
    }
    return s;
}

std::string targetIds(const std::vector<BenchTarget>& targets) {
    std::vector<std::string> ids;
    for (const BenchTarget& t : targets) ids.push_back(t.id());
    return join(ids, ' ');
}

std::string methodNames(const std::vector<Method>& methods) {
    std::vector<std::string> names;
    for (Method m : methods) names.push_back(methodName(m));
    return join(names, ' ');
}

std::string benchScriptDir(const std::string& configured) {
    if (!configured.empty()) return configured;
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec && fs::exists(exe.parent_path() / "bench" / "accuracy.gp"))
        return (exe.parent_path() / "bench").string();
#ifdef CLOTH_SOURCE_BENCH_DIR
    return CLOTH_SOURCE_BENCH_DIR;
#else
    return "bench";
#endif
}

namespace {

// A gnuplot string literal: single quotes, a quote inside doubled.
std::string quoted(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("''") : std::string(1, c);
    return q + "'";
}

// Runs argv, its stdout sent to stderr; returns the exit status, or -1 with errno when it could
// not start (ENOENT: not installed).
int spawn(const std::vector<std::string>& argv) {
    std::vector<char*> cargs;
    for (const std::string& a : argv) cargs.push_back(const_cast<char*>(a.c_str()));
    cargs.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, STDERR_FILENO, STDOUT_FILENO);
    pid_t pid = 0;
    const int err = posix_spawnp(&pid, argv[0].c_str(), &actions, nullptr, cargs.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (err != 0) {
        errno = err;
        return -1;
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

PlotVars seriesVars(const std::vector<std::pair<Method, BenchTarget>>& curves) {
    auto colour = [](Method m) {
        return std::to_string(std::find(std::begin(kMethods), std::end(kMethods), m) -
                              std::begin(kMethods) + 1);
    };
    std::vector<std::string> methods, targets, colours, styles;
    std::vector<std::string> uniqueMethods, uniqueColours, uniqueTargets;
    for (const auto& [m, t] : curves) {
        methods.push_back(methodName(m));
        targets.push_back(t.id());
        colours.push_back(colour(m));
        styles.push_back(t.backend == Backend::Gpu          ? "3"
                         : t.precision == Precision::Double ? "1"
                                                            : "2");
        if (std::find(uniqueMethods.begin(), uniqueMethods.end(), methods.back()) ==
            uniqueMethods.end()) {
            uniqueMethods.push_back(methods.back());
            uniqueColours.push_back(colours.back());
            uniqueTargets.push_back(targets.back());
        }
    }
    return {
        {"series_methods", join(methods, ' ')},      {"series_targets", join(targets, ' ')},
        {"series_colours", join(colours, ' ')},      {"series_styles", join(styles, ' ')},
        {"methods", join(uniqueMethods, ' ')},       {"method_colours", join(uniqueColours, ' ')},
        {"method_targets", join(uniqueTargets, ' ')}};
}

std::vector<std::string> plot(const std::string& scriptDir, const std::string& script,
                              const std::string& outStem, const PlotVars& vars) {
    const std::string path = (fs::path(benchScriptDir(scriptDir)) / script).string();
    std::vector<std::string> written;
    for (const char* format : {"png", "svg"}) {
        const std::string file = outStem + "." + format;
        std::string setup = "format=" + quoted(format) + "; out=" + quoted(file) + ";";
        for (const auto& [name, value] : vars) setup += " " + name + "=" + quoted(value) + ";";
        const int status = spawn({"gnuplot", "-e", setup, path});
        if (status < 0 && errno == ENOENT) {
            std::fprintf(stderr,
                         "clothsim bench: gnuplot is not installed, so no plot was drawn (the "
                         "CSV has the numbers; apt-get install gnuplot-nox)\n");
            return {};
        }
        if (status != 0) {
            std::fprintf(stderr, "clothsim bench: gnuplot %s failed (status %d); no %s plot\n",
                         path.c_str(), status, format);
            std::error_code ec;
            fs::remove(file, ec);  // what a failed run left behind is no plot
            continue;
        }
        written.push_back(file);
    }
    return written;
}

}  // namespace cloth::app
