#include "solver/output.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "solver/diagnostics.h"
#include "model/forces.h"

namespace cloth {
namespace {

// Writes through a temporary file in the same directory, renamed into place on success.
class AtomicFile {
public:
    explicit AtomicFile(const std::string& path) : path_(path), tmp_(path + ".tmp") {
        file_ = std::fopen(tmp_.c_str(), "w");
        if (!file_) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
    }
    ~AtomicFile() {
        if (file_) {
            std::fclose(file_);
            std::remove(tmp_.c_str());
        }
    }
    FILE* get() { return file_; }
    void commit() {
        const bool ok = std::fflush(file_) == 0 && !std::ferror(file_);
        std::fclose(file_);
        file_ = nullptr;
        if (!ok || std::rename(tmp_.c_str(), path_.c_str()) != 0) {
            std::remove(tmp_.c_str());
            throw std::runtime_error("cannot write " + path_ + ": " + std::strerror(errno));
        }
    }

private:
    std::string path_, tmp_;
    FILE* file_ = nullptr;
};

void requireFinite(const SimState& state, const std::string& path) {
    if (!allFinite(state))
        throw std::runtime_error("refusing to write " + path + ": the state has non-finite values");
}

}  // namespace

void writeCsv(const std::string& path, const SimState& state, Precision precision) {
    requireFinite(state, path);
    AtomicFile out(path);
    FILE* f = out.get();
    const char* row = precision == Precision::Double ? "%d,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n"
                                                     : "%d,%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n";
    std::fputs("i,j,x,y,z,vx,vy,vz\n", f);
    for (int j = 0; j < state.nv; ++j) {
        for (int i = 0; i < state.nu; ++i) {
            const size_t k = size_t(j) * state.nu + i;
            const glm::dvec3 &p = state.positions[k], &v = state.velocities[k];
            std::fprintf(f, row, i, j, p.x, p.y, p.z, v.x, v.y, v.z);
        }
    }
    out.commit();
}

void writeObj(const std::string& path, const SimState& state, const std::string& sceneName) {
    requireFinite(state, path);
    AtomicFile out(path);
    FILE* f = out.get();
    const int nu = state.nu, nv = state.nv;
    auto at = [&](int i, int j) { return state.positions[size_t(j) * nu + i]; };
    std::fprintf(f, "# clothsim: %s, %d x %d vertices\no %s\n", sceneName.c_str(), nu, nv,
                 sceneName.c_str());
    for (const glm::dvec3& p : state.positions)
        std::fprintf(f, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i)
            std::fprintf(f, "vt %.9g %.9g\n", nu > 1 ? double(i) / (nu - 1) : 0.0,
                         nv > 1 ? double(j) / (nv - 1) : 0.0);
    for (int j = 0; j < nv; ++j) {
        for (int i = 0; i < nu; ++i) {
            const glm::dvec3 n = vertexNormal<double>(nu, nv, i, j, at);
            std::fprintf(f, "vn %.6f %.6f %.6f\n", n.x, n.y, n.z);
        }
    }
    if (nu == 1 || nv == 1) {
        std::fputs("l", f);
        for (int k = 1; k <= nu * nv; ++k) std::fprintf(f, " %d/%d", k, k);
        std::fputs("\n", f);
    } else {
        // OBJ indices are 1-based; the normal a × b points along û × v̂ at rest, so (k, k+1,
        // k+nu+1) is counter-clockwise seen from the normal's side.
        for (int j = 0; j + 1 < nv; ++j) {
            for (int i = 0; i + 1 < nu; ++i) {
                const long a = long(j) * nu + i + 1, b = a + 1, c = a + nu + 1, d = a + nu;
                std::fprintf(f, "f %ld/%ld/%ld %ld/%ld/%ld %ld/%ld/%ld\n", a, a, a, b, b, b, c, c,
                             c);
                std::fprintf(f, "f %ld/%ld/%ld %ld/%ld/%ld %ld/%ld/%ld\n", a, a, a, c, c, c, d, d,
                             d);
            }
        }
    }
    out.commit();
}

}  // namespace cloth
