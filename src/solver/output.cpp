#include "solver/output.h"

#include <bit>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "model/forces.h"
#include "model/output_file.h"
#include "solver/diagnostics.h"

namespace cloth {
namespace {

void requireFinite(const SimState& state, const std::string& path) {
    if (!allFinite(state))
        throw std::runtime_error("refusing to write " + path + ": the state has non-finite values");
}

// PC2 is little-endian whatever the host is: each 32-bit word goes out low byte first.
void appendWord(std::string& bytes, std::uint32_t word) {
    for (int shift = 0; shift < 32; shift += 8) bytes.push_back(char((word >> shift) & 0xffu));
}

void appendFloat(std::string& bytes, double x) {
    appendWord(bytes, std::bit_cast<std::uint32_t>(float(x)));
}

constexpr long kMaxPc2Count = std::numeric_limits<std::int32_t>::max();

}  // namespace

void writeCsv(const std::string& path, const SimState& state, Precision precision) {
    requireFinite(state, path);
    OutputFile out(path);
    const char* row = precision == Precision::Double ? "%d,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n"
                                                     : "%d,%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n";
    out.write("i,j,x,y,z,vx,vy,vz\n");
    for (int j = 0; j < state.nv; ++j) {
        for (int i = 0; i < state.nu; ++i) {
            const size_t k = size_t(j) * state.nu + i;
            const glm::dvec3 &p = state.positions[k], &v = state.velocities[k];
            out.print(row, i, j, p.x, p.y, p.z, v.x, v.y, v.z);
        }
    }
    out.commit();
}

void writeObj(const std::string& path, const SimState& state, const std::string& sceneName) {
    requireFinite(state, path);
    OutputFile out(path);
    const int nu = state.nu, nv = state.nv;
    auto at = [&](int i, int j) { return state.positions[size_t(j) * nu + i]; };
    out.print("# clothsim: %s, %d x %d vertices\no %s\n", sceneName.c_str(), nu, nv,
              sceneName.c_str());
    for (const glm::dvec3& p : state.positions) out.print("v %.9g %.9g %.9g\n", p.x, p.y, p.z);
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i)
            out.print("vt %.9g %.9g\n", nu > 1 ? double(i) / (nu - 1) : 0.0,
                      nv > 1 ? double(j) / (nv - 1) : 0.0);
    for (int j = 0; j < nv; ++j) {
        for (int i = 0; i < nu; ++i) {
            const glm::dvec3 n = vertexNormal<double>(nu, nv, i, j, at);
            out.print("vn %.6f %.6f %.6f\n", n.x, n.y, n.z);
        }
    }
    if (nu == 1 || nv == 1) {
        // A segment per `l`: Blender 3.4's importer makes one edge of a longer `l` and drops the
        // vertices past its second, which a point cache played on this OBJ needs.
        for (int k = 1; k < nu * nv; ++k) out.print("l %d/%d %d/%d\n", k, k, k + 1, k + 1);
    } else {
        // OBJ indices are 1-based; the normal a × b points along û × v̂ at rest, so (k, k+1,
        // k+nu+1) is counter-clockwise seen from the normal's side.
        for (int j = 0; j + 1 < nv; ++j) {
            for (int i = 0; i + 1 < nu; ++i) {
                const long a = long(j) * nu + i + 1, b = a + 1, c = a + nu + 1, d = a + nu;
                out.print("f %ld/%ld/%ld %ld/%ld/%ld %ld/%ld/%ld\n", a, a, a, b, b, b, c, c, c);
                out.print("f %ld/%ld/%ld %ld/%ld/%ld %ld/%ld/%ld\n", a, a, a, c, c, c, d, d, d);
            }
        }
    }
    out.commit();
}

Pc2Writer::Pc2Writer(const std::string& path, long points, long samples)
    : path_(path), out_(path), points_(points), samples_(samples) {
    if (points < 1 || points > kMaxPc2Count || samples < 1 || samples > kMaxPc2Count)
        throw std::invalid_argument("PC2 counts " + std::to_string(points) + " points, " +
                                    std::to_string(samples) + " samples: not in [1, 2^31 - 1]");
    std::string header("POINTCACHE2", 12);  // the signature with its NUL
    appendWord(header, 1);                  // version
    appendWord(header, std::uint32_t(points));
    appendFloat(header, 0.0);  // start frame
    appendFloat(header, 1.0);  // sample rate: frames per sample
    appendWord(header, std::uint32_t(samples));
    out_.write(header);
}

void Pc2Writer::add(const SimState& state) {
    requireFinite(state, path_);
    if (long(state.positions.size()) != points_ || added_ == samples_)
        throw std::logic_error("PC2 " + path_ + ": a sample of " +
                               std::to_string(state.positions.size()) + " points after " +
                               std::to_string(added_) + " of " + std::to_string(samples_) +
                               " samples of " + std::to_string(points_));
    std::string bytes;
    bytes.reserve(12 * state.positions.size());
    for (const glm::dvec3& p : state.positions)
        for (int c = 0; c < 3; ++c) appendFloat(bytes, p[c]);
    out_.write(bytes);
    ++added_;
}

void Pc2Writer::commit() {
    if (added_ != samples_)
        throw OutputError(path_, std::to_string(added_) + " samples written of the " +
                                     std::to_string(samples_) + " its header counts");
    out_.commit();
}

}  // namespace cloth
