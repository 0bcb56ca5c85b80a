#include "model/mesh_sdf.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <thread>
#include <unordered_map>

#include "model/errors.h"

namespace cloth {
namespace {

[[noreturn]] void fail(const MeshSource& src, const std::string& objPath, const std::string& why) {
    const std::string file = src.file.empty() ? objPath : src.file;
    const std::string reason = src.file.empty() ? why : "'" + objPath + "': " + why;
    throw InputError(file, src.key, reason);
}

std::string edgeName(std::uint32_t a, std::uint32_t b) {
    return "edge (" + std::to_string(a + 1) + ", " + std::to_string(b + 1) + ")";
}

// The first `v` line whose x, y and z are not three finite numbers ("line 12: 'v 0 0 abc'"):
// tinyobjloader reads a word or a missing coordinate as 0 and would give the mesh another shape.
std::optional<std::string> badVertexLine(const std::string& objPath) {
    std::ifstream in(objPath);
    std::string line;
    for (long number = 1; std::getline(in, line); ++number) {
        std::istringstream words(line);
        std::string word;
        if (!(words >> word) || word != "v") continue;
        int numbers = 0;
        for (; numbers < 3 && words >> word; ++numbers) {
            char* end = nullptr;
            const double x = std::strtod(word.c_str(), &end);
            if (end != word.c_str() + word.size() || !std::isfinite(x)) break;
        }
        if (numbers < 3) {
            if (!line.empty() && line.back() == '\r') line.pop_back();
            return "line " + std::to_string(number) + ": '" + line.substr(0, 80) +
                   "': a vertex needs three finite numbers";
        }
    }
    return std::nullopt;
}

}  // namespace

TriMesh loadObjMesh(const std::string& objPath, const MeshSource& source) {
    std::error_code ec;
    if (!std::filesystem::exists(objPath, ec)) fail(source, objPath, "no such file");
    if (!std::filesystem::is_regular_file(objPath, ec))
        fail(source, objPath, "not a regular file (an OBJ file is needed)");
    if (const auto bad = badVertexLine(objPath)) fail(source, objPath, *bad);
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(objPath, config))
        fail(source, objPath, "cannot read the OBJ: " + reader.Error());
    const std::vector<tinyobj::real_t>& v = reader.GetAttrib().vertices;
    TriMesh mesh;
    // Weld: OBJ writers often repeat a position per face (split normals or UVs); the manifold
    // check and the winding number need the shared vertex.
    std::map<std::array<double, 3>, std::uint32_t> weld;
    std::vector<std::uint32_t> remap(v.size() / 3);
    for (size_t k = 0; k < v.size() / 3; ++k) {
        const std::array<double, 3> x{v[3 * k], v[3 * k + 1], v[3 * k + 2]};
        if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
            fail(source, objPath, "vertex " + std::to_string(k + 1) + " is not finite");
        const auto [it, added] = weld.try_emplace(x, std::uint32_t(mesh.vertices.size()));
        if (added) mesh.vertices.emplace_back(x[0], x[1], x[2]);
        remap[k] = it->second;
    }
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        const std::vector<tinyobj::index_t>& idx = shape.mesh.indices;
        size_t at = 0;
        for (const unsigned char n : shape.mesh.num_face_vertices) {
            if (n == 3) {
                std::array<std::uint32_t, 3> t;
                for (int c = 0; c < 3; ++c) {
                    const int vi = idx[at + c].vertex_index;
                    if (vi < 0 || size_t(vi) >= remap.size())
                        fail(source, objPath, "a face refers to a vertex that does not exist");
                    t[c] = remap[size_t(vi)];
                }
                mesh.triangles.push_back(t);
            }
            at += n;
        }
    }
    if (mesh.triangles.empty()) fail(source, objPath, "the OBJ has no triangles");
    if (const auto problem = closedManifoldProblem(mesh))
        fail(source, objPath, "the mesh is not closed and manifold: " + *problem);
    return mesh;
}

std::optional<std::string> closedManifoldProblem(const TriMesh& mesh) {
    if (mesh.triangles.empty()) return "it has no triangles";
    // Directed edge → how many triangles use it in that direction.
    std::unordered_map<std::uint64_t, int> directed;
    const auto key = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t(a) << 32) | b; };
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
            return "triangle " + std::to_string(t + 1) + " repeats a vertex";
        for (int e = 0; e < 3; ++e) ++directed[key(tri[e], tri[(e + 1) % 3])];
    }
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        for (int e = 0; e < 3; ++e) {
            const std::uint32_t a = tri[e], b = tri[(e + 1) % 3];
            const int same = directed[key(a, b)];
            const auto twin = directed.find(key(b, a));
            const int opposite = twin == directed.end() ? 0 : twin->second;
            if (same > 1)
                return edgeName(a, b) + " is used by " + std::to_string(same) +
                       " triangles in the same direction (non-manifold or inconsistently "
                       "oriented)";
            if (opposite == 0)
                return edgeName(a, b) + " of triangle " + std::to_string(t + 1) +
                       " has no neighbour across it (the mesh is not closed)";
            if (opposite > 1)
                return edgeName(a, b) + " is shared by " + std::to_string(opposite + 1) +
                       " triangles (non-manifold)";
        }
    }
    return std::nullopt;
}

// Ericson, Real-Time Collision Detection §5.1.5: the closest point by Voronoi region.
double pointTriangleDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                             const glm::dvec3& c) {
    const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return glm::length(ap);
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return glm::length(bp);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return glm::length(ap - d1 / (d1 - d3) * ab);
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return glm::length(cp);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return glm::length(ap - d2 / (d2 - d6) * ac);
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return glm::length(bp - (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b));
    const double denom = 1 / (va + vb + vc);
    return glm::length(ap - (vb * denom) * ab - (vc * denom) * ac);
}

double windingNumber(const TriMesh& mesh, const glm::dvec3& p) {
    double total = 0;
    for (const auto& t : mesh.triangles) {
        const glm::dvec3 a = mesh.vertices[t[0]] - p, b = mesh.vertices[t[1]] - p,
                         c = mesh.vertices[t[2]] - p;
        const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
        const double num = glm::dot(a, glm::cross(b, c));
        const double den =
            la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
        total += 2 * std::atan2(num, den);  // the triangle's signed solid angle
    }
    return total / (4 * std::numbers::pi);
}

namespace {

// A bounding sphere per triangle (centroid, farthest corner): a triangle whose sphere is farther
// than the best distance so far cannot be nearer, so the exact test is skipped.
struct TriangleBounds {
    std::vector<glm::dvec3> centre;
    std::vector<double> radius;
    explicit TriangleBounds(const TriMesh& m) {
        for (const auto& t : m.triangles) {
            const glm::dvec3 c = (m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]]) / 3.0;
            double r = 0;
            for (const std::uint32_t v : t) r = std::max(r, glm::length(m.vertices[v] - c));
            centre.push_back(c);
            radius.push_back(r);
        }
    }
};

double unsignedDistance(const TriMesh& m, const TriangleBounds& b, const glm::dvec3& p) {
    double best = INFINITY;
    for (size_t t = 0; t < m.triangles.size(); ++t) {
        if (glm::length(p - b.centre[t]) - b.radius[t] >= best) continue;
        const auto& tri = m.triangles[t];
        best = std::min(best, pointTriangleDistance(p, m.vertices[tri[0]], m.vertices[tri[1]],
                                                    m.vertices[tri[2]]));
    }
    return best;
}

// One row along x of the grid. The sign comes from the winding number only where it must: if
// the distance d at a sample exceeds the cell, the open ball of radius d holds no surface, so the
// segment from the previous sample of the row (one cell away, strictly inside that ball, hence
// not on the surface itself) does not cross it and the sign carries over. The margin keeps a
// previous sample that lies on the surface (its sign arbitrary) from passing its sign on when
// rounding makes d a hair larger than an exact cell.
void bakeRow(const TriMesh& m, const TriangleBounds& b, SdfGrid& g, int row) {
    const int j = row % g.count.y, k = row / g.count.y;
    bool inside = false;
    for (int i = 0; i < g.count.x; ++i) {
        const glm::dvec3 p = g.origin + g.cell * glm::dvec3(i, j, k);
        const double d = unsignedDistance(m, b, p);
        if (i == 0 || !(d > g.cell * (1 + 1e-9))) inside = std::abs(windingNumber(m, p)) > 0.5;
        g.values[size_t(g.index(i, j, k))] = inside ? -d : d;
    }
}

}  // namespace

SdfGrid bakeSdf(const TriMesh& mesh, double cell, double band, const MeshSource& source) {
    if (!(cell > 0) || !std::isfinite(cell))
        throw InputError(source.file, source.key, "the grid cell must be > 0");
    if (!(band >= 0) || !std::isfinite(band))
        throw InputError(source.file, source.key, "the band must be ≥ 0");
    if (mesh.triangles.empty()) throw InputError(source.file, source.key, "the mesh is empty");
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::dvec3& v : mesh.vertices) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    // A cell past half the mesh's largest extent leaves the grid fewer than two cells across the
    // mesh: the trilinear field (error up to (√3/2)·cell) is then a blur, not the mesh's shape.
    const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    if (cell > extent / 2) {
        std::ostringstream why;
        why.precision(3);
        why << "the grid cell " << cell << " m leaves fewer than 2 cells across the mesh (its "
            << "largest extent is " << extent << " m): a cell of at most " << extent / 10
            << " m resolves its shape";
        throw InputError(source.file, source.key, why.str());
    }
    lo -= band;
    hi += band;
    SdfGrid g;
    g.origin = lo;
    g.cell = cell;
    g.band = band;
    std::int64_t total = 1;
    for (int a = 0; a < 3; ++a) {
        const double n = std::ceil((hi[a] - lo[a]) / cell) + 1;
        if (!(n <= double(kMaxSdfSamples)))
            throw InputError(source.file, source.key, "grid cell too fine for memory");
        g.count[a] = std::max(2, int(n));
        total *= g.count[a];
        if (total > kMaxSdfSamples)
            throw InputError(source.file, source.key,
                             "grid cell " + std::to_string(cell) +
                                 " m too fine for memory (more than " +
                                 std::to_string(kMaxSdfSamples) + " samples)");
    }
    g.values.resize(size_t(total));
    // Rows along x are independent: share them out over the cores.
    const int rows = g.count.y * g.count.z;
    const int threads = std::clamp(int(std::thread::hardware_concurrency()), 1, 16);
    std::vector<std::thread> pool;
    std::atomic<int> next{0};
    const TriangleBounds bounds(mesh);
    for (int t = 0; t < threads; ++t)
        pool.emplace_back([&] {
            for (int row = next++; row < rows; row = next++) bakeRow(mesh, bounds, g, row);
        });
    for (std::thread& t : pool) t.join();
    return g;
}

}  // namespace cloth
