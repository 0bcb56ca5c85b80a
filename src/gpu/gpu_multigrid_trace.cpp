// GpuMultigrid::describe: the hierarchy's buffers read back and summed up level by level, to see
// where a V-cycle went wrong on a device (CLOTH_MULTIGRID_TRACE; README, "Environment"). The
// offsets are multigrid.glsl's.
#include <GL/glew.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "gpu/gpu_multigrid.h"

namespace cloth {
namespace {

std::vector<double> download(unsigned buffer, long long bytes) {
    std::vector<double> out(std::size_t(bytes) / sizeof(double));
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(bytes), out.data());
    return out;
}

// The range of some values and how many were not finite.
struct Range {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    long bad = 0;
    void add(double v) {
        if (!std::isfinite(v)) {
            ++bad;
            return;
        }
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    std::string text() const {
        char s[64];
        if (lo > hi) return "[none]";
        std::snprintf(s, sizeof s, "[%.3g, %.3g]", lo, hi);
        return s;
    }
};

}  // namespace

std::string GpuMultigrid::describe() const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const std::vector<double> stencil = download(stencil_, bytes_.stencil);
    const std::vector<double> work = download(work_, bytes_.work);
    long long total = 0;
    for (const MultigridLevel& l : levels_) total += l.count();
    std::string out;
    long long first = 0;
    for (int level = 0; level < levels(); ++level) {
        const MultigridLevel& l = levels_[std::size_t(level)];
        const long long n = l.count();
        Range diagonal, lines[2], r, z;
        long stencilBad = 0, vectorBad = 0;
        double rz = 0;  // r·z: on the fine grid the first V-cycle's, whose sign the CG needs
        for (long long k = 0; k < n; ++k) {
            const std::size_t block = std::size_t((first + k) * 25) * 9;
            for (std::size_t e = 0; e < 225; ++e)
                if (!std::isfinite(stencil[block + e])) ++stencilBad;
            for (std::size_t c = 0; c < 3; ++c) diagonal.add(stencil[block + 12 * 9 + 4 * c]);
            const std::size_t at = std::size_t(54 * total + 9 * (first + k));
            for (std::size_t c = 0; c < 3; ++c) {
                r.add(std::abs(work[at + c]));
                rz += work[at + c] * work[at + 3 + c];
                z.add(std::abs(work[at + 3 + c]));
                if (!std::isfinite(work[at + 6 + c])) ++vectorBad;
            }
        }
        vectorBad += r.bad + z.bad;
        if (level + 1 < levels()) {  // the coarsest grid has its dense factor instead
            for (int direction = 0; direction < 2; ++direction) {
                const std::size_t base = std::size_t(54 * first + (direction == 0 ? 0 : 27 * n));
                for (long long row = 0; row < 3 * n; ++row) {  // every line's rows, in turn
                    for (std::size_t e = 0; e < 8; ++e)
                        if (!std::isfinite(work[base + std::size_t(row) * 9 + e]))
                            ++lines[direction].bad;
                    lines[direction].add(work[base + std::size_t(row) * 9 + 8]);
                }
            }
        }
        char line[512];
        std::snprintf(line, sizeof line,
                      "  level %d, %dx%d: A_kk's diagonal %s; line factors' L_ii: rows %s, "
                      "columns %s; |r| %s, |z| %s, r·z %.17g; not finite: %ld in the stencil, %ld "
                      "in the line factors, %ld in r, z, t\n",
                      level, l.nu, l.nv, diagonal.text().c_str(),
                      level + 1 < levels() ? lines[0].text().c_str() : "(dense)",
                      level + 1 < levels() ? lines[1].text().c_str() : "(dense)", r.text().c_str(),
                      z.text().c_str(), rz, stencilBad, lines[0].bad + lines[1].bad, vectorBad);
        out += line;
        first += n;
    }
    const long long dofs = 3 * levels_.back().count();
    Range factor;
    long factorBad = 0;
    for (long long i = 0; i < dofs; ++i) {
        for (long long j = 0; j < i; ++j)
            if (!std::isfinite(work[std::size_t(63 * total + i * dofs + j)])) ++factorBad;
        factor.add(work[std::size_t(63 * total + i * dofs + i)]);
    }
    char line[256];
    std::snprintf(line, sizeof line,
                  "  coarsest grid's dense factor (%lld unknowns): L_ii %s; not finite: %ld\n",
                  dofs, factor.text().c_str(), factorBad + factor.bad);
    return out + line;
}

}  // namespace cloth
