#include "app/cli.h"

#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>

#include "model/errors.h"
#include "model/output_file.h"
#include "scene/scene_overrides.h"

namespace cloth::app {

void addSet(std::vector<std::string>& sets, std::string assignment,
            std::vector<std::string>* notices) {
    for (const std::string& notice : replacedOverrides(sets, assignment)) {
        if (notices)
            notices->push_back(notice);
        else
            std::fprintf(stderr, "clothsim: note: %s\n", notice.c_str());
    }
    sets.push_back(std::move(assignment));
}

Args::Args(std::string command, std::vector<std::string> args)
    : command_(std::move(command)), args_(std::move(args)) {}

std::string Args::next() {
    if (done()) throw InputError("command line", command_, "missing argument");
    return args_[pos_++];
}

std::string Args::flag() {
    std::string a = next();
    const size_t eq = a.find('=');
    hasPending_ = a.rfind("--", 0) == 0 && eq != std::string::npos;
    if (hasPending_) {
        pendingValue_ = a.substr(eq + 1);
        a = a.substr(0, eq);
    }
    return a;
}

std::string Args::value(const std::string& f) {
    if (hasPending_) {
        hasPending_ = false;
        if (pendingValue_.empty()) throw InputError("command line", f, "needs a value, got ''");
        return pendingValue_;
    }
    if (done()) throw InputError("command line", f, "needs a value");
    const std::string& v = args_[pos_];
    // A flag where the value should be (`--out-csv --quiet`) is a value forgotten, not a file.
    if (v.rfind("--", 0) == 0)
        throw InputError("command line", f, "needs a value; '" + v + "' is the next option");
    if (v.empty()) throw InputError("command line", f, "needs a value, got ''");
    return args_[pos_++];
}

long Args::positiveInt(const std::string& f) {
    const std::string v = value(f);
    char* end = nullptr;
    errno = 0;
    const long n = std::strtol(v.c_str(), &end, 10);
    if (v.empty() || *end != '\0' || errno == ERANGE || n <= 0)
        throw InputError("command line", f, "expected a positive integer, got '" + v + "'");
    return n;
}

int Args::positiveInt32(const std::string& f) {
    const long n = positiveInt(f);
    if (n > std::numeric_limits<std::int32_t>::max())
        throw InputError("command line", f,
                         "expected a positive integer below 2^31, got " + std::to_string(n));
    return int(n);
}

bool Args::takeScene(std::string& scenePath) {
    if (done() || isFlag()) return false;
    const std::string a = next();
    if (sceneTaken_) throw InputError("command line", a, "only one scene may be given");
    scenePath = a;
    sceneTaken_ = true;
    return true;
}

void Args::unknown(const std::string& f) const {
    throw InputError("command line", f,
                     "unknown option for '" + command_ + "'; see clothsim " + command_ + " --help");
}

void checkOutputFile(const std::string& flag, const std::string& file) {
    if (file.empty()) return;
    const OutputTarget target = resolveOutput(file);
    if (target.kind == OutputTarget::Kind::Unusable)
        throw InputError("command line", flag, "cannot write '" + file + "': " + target.reason);
}

void checkDistinctFiles(const std::vector<std::pair<std::string, std::string>>& files) {
    namespace fs = std::filesystem;
    std::vector<std::pair<const std::string*, fs::path>> seen;  // flag, the file written
    for (const auto& [flag, path] : files) {
        if (path.empty()) continue;
        const OutputTarget target = resolveOutput(path);
        if (target.kind != OutputTarget::Kind::Replace) continue;
        std::error_code ec;
        fs::path file = fs::weakly_canonical(fs::absolute(target.file), ec);
        if (ec) continue;  // checkOutputFile or the loader says what is wrong with it
        for (const auto& [other, earlier] : seen)
            if (earlier == file)
                throw InputError("command line", flag,
                                 "'" + path + "' is the file " + *other + " names (" +
                                     file.string() + "): give each output a file of its own");
        seen.emplace_back(&flag, std::move(file));
    }
}

void prepareFramesDir(const std::string& flag, const std::string& dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec)
        throw InputError("command line", flag,
                         "cannot make directory '" + dir + "': " + ec.message());
    if (!fs::is_directory(dir, ec))
        throw InputError("command line", flag, "'" + dir + "' is not a directory");
    if (::access(dir.c_str(), W_OK) != 0)
        throw InputError("command line", flag,
                         "directory '" + dir + "' is not writable: " + std::strerror(errno));
}

}  // namespace cloth::app
