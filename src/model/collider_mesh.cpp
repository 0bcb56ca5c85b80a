#include "model/collider_mesh.h"

#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>

#include "model/mesh_sdf.h"
#include "model/output_file.h"

namespace cloth {
namespace {

using Tri = std::array<std::uint32_t, 3>;

// Two unit vectors completing the unit `w` to a right-handed frame (e1 × e2 = w).
void frame(const glm::dvec3& w, glm::dvec3& e1, glm::dvec3& e2) {
    const glm::dvec3 a = std::abs(w.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    e1 = glm::normalize(glm::cross(a, w));
    e2 = glm::cross(w, e1);
}

std::uint32_t add(TriMesh& m, const glm::dvec3& p) {
    m.vertices.push_back(p);
    return std::uint32_t(m.vertices.size() - 1);
}

}  // namespace

TriMesh planeQuad(const PlaneT<double>& plane, double halfSize) {
    glm::dvec3 e1, e2;
    frame(glm::normalize(plane.normal), e1, e2);
    TriMesh m;
    for (const auto& [s, t] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
        add(m, plane.point + halfSize * (double(s) * e1 + double(t) * e2));
    m.triangles = {{0, 1, 2}, {0, 2, 3}};  // counter-clockwise about e1 × e2 = n
    return m;
}

TriMesh sphereMesh(const SphereT<double>& sphere, int subdivisions) {
    const double t = (1 + std::sqrt(5.0)) / 2;
    std::vector<glm::dvec3> unit = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                    {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                    {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (auto& v : unit) v = glm::normalize(v);
    std::vector<Tri> tris = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                             {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                             {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                             {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int s = 0; s < subdivisions; ++s) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
        const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::minmax(a, b);
            const auto [it, added] = mid.try_emplace(key, std::uint32_t(unit.size()));
            if (added) unit.push_back(glm::normalize(unit[a] + unit[b]));
            return it->second;
        };
        std::vector<Tri> next;
        for (const Tri& f : tris) {
            const std::uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]),
                                ca = midpoint(f[2], f[0]);
            next.insert(next.end(), {{f[0], ab, ca}, {f[1], bc, ab}, {f[2], ca, bc}, {ab, bc, ca}});
        }
        tris = std::move(next);
    }
    TriMesh m;
    for (const auto& u : unit) m.vertices.push_back(sphere.center + sphere.radius * u);
    m.triangles = std::move(tris);
    return m;
}

TriMesh boxMesh(const BoxT<double>& box) {
    TriMesh m;
    for (int k = 0; k < 8; ++k) {  // corner k: bit 0 → +x, bit 1 → +y, bit 2 → +z
        const glm::dvec3 s((k & 1) ? 1 : -1, (k & 2) ? 1 : -1, (k & 4) ? 1 : -1);
        add(m, box.center + box.rotation * (s * box.halfExtents));
    }
    m.triangles = {{0, 4, 6}, {0, 6, 2},   // −x
                   {1, 3, 7}, {1, 7, 5},   // +x
                   {0, 1, 5}, {0, 5, 4},   // −y
                   {2, 6, 7}, {2, 7, 3},   // +y
                   {0, 2, 3}, {0, 3, 1},   // −z
                   {4, 5, 7}, {4, 7, 6}};  // +z
    return m;
}

TriMesh capsuleMesh(const CapsuleT<double>& c, int slices, int stacks) {
    const glm::dvec3 ab = c.b - c.a;
    const glm::dvec3 w = glm::length(ab) > 0 ? glm::normalize(ab) : glm::dvec3(0, 1, 0);
    glm::dvec3 e1, e2;
    frame(w, e1, e2);
    TriMesh m;
    const std::uint32_t poleA = add(m, c.a - c.radius * w);
    // Rings from the a pole to the b pole: `stacks` on each hemisphere (the equators included).
    int rings = 0;
    for (int half = 0; half < 2; ++half) {
        for (int s = 1; s <= stacks; ++s) {
            const int step = half == 0 ? s : stacks + 1 - s;
            const double theta = 0.5 * std::numbers::pi * double(step) / stacks;  // from the pole
            const glm::dvec3 centre = half == 0 ? c.a - c.radius * std::cos(theta) * w
                                                : c.b + c.radius * std::cos(theta) * w;
            for (int l = 0; l < slices; ++l) {
                const double phi = 2 * std::numbers::pi * double(l) / slices;
                add(m, centre +
                           c.radius * std::sin(theta) * (std::cos(phi) * e1 + std::sin(phi) * e2));
            }
            ++rings;
        }
    }
    const std::uint32_t poleB = add(m, c.b + c.radius * w);
    const auto at = [&](int ring, int l) { return std::uint32_t(1 + ring * slices + l % slices); };
    for (int l = 0; l < slices; ++l) {
        // Around −w seen from outside at the a pole, e2 → e1 is counter-clockwise.
        m.triangles.push_back({poleA, at(0, l + 1), at(0, l)});
        for (int r = 0; r + 1 < rings; ++r) {
            m.triangles.push_back({at(r, l), at(r, l + 1), at(r + 1, l + 1)});
            m.triangles.push_back({at(r, l), at(r + 1, l + 1), at(r + 1, l)});
        }
        m.triangles.push_back({poleB, at(rings - 1, l), at(rings - 1, l + 1)});
    }
    return m;
}

std::vector<std::pair<std::string, TriMesh>> colliderMeshes(const std::vector<Collider>& colliders,
                                                            double planeHalfSize) {
    std::vector<std::pair<std::string, TriMesh>> out;
    for (size_t k = 0; k < colliders.size(); ++k) {
        const std::string name = "collider" + std::to_string(k);
        const Collider& c = colliders[k];
        const std::string type = colliderTypeName(c.shape);
        if (const Plane* p = c.as<Plane>())
            out.emplace_back(name + "_" + type, planeQuad({p->point, p->normal}, planeHalfSize));
        else if (const Sphere* s = c.as<Sphere>())
            out.emplace_back(name + "_" + type, sphereMesh({s->center, s->radius}, 3));
        else if (const Box* b = c.as<Box>())
            out.emplace_back(name + "_" + type,
                             boxMesh({b->center, b->halfExtents, b->rotation.matrix()}));
        else if (const Capsule* cap = c.as<Capsule>())
            out.emplace_back(name + "_" + type, capsuleMesh({cap->a, cap->b, cap->radius}, 32, 8));
        else if (const MeshCollider* m = c.as<MeshCollider>()) {
            TriMesh posed = m->baked->mesh;  // the OBJ rotated about its origin, then moved
            const glm::dmat3 r = m->rotation.matrix();
            for (glm::dvec3& v : posed.vertices) v = r * v + m->translation;
            out.emplace_back(name + "_" + type, std::move(posed));
        }
    }
    return out;
}

void writeMeshesObj(const std::string& path,
                    const std::vector<std::pair<std::string, TriMesh>>& meshes) {
    for (const auto& [name, m] : meshes)
        for (const glm::dvec3& v : m.vertices)
            if (!std::isfinite(v.x + v.y + v.z))
                throw std::runtime_error("refusing to write " + path + ": " + name +
                                         " has non-finite vertices");
    OutputFile out(path);
    out.write("# clothsim colliders\n");
    size_t base = 1;  // OBJ indices are 1-based and global to the file
    for (const auto& [name, m] : meshes) {
        std::vector<glm::dvec3> normals(m.vertices.size(), glm::dvec3(0));
        for (const auto& t : m.triangles) {
            const glm::dvec3 a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
            const glm::dvec3 n = glm::cross(b - a, c - a);  // length = 2·area: area-weighted
            for (const std::uint32_t v : t) normals[v] += n;
        }
        out.print("o %s\n", name.c_str());
        for (const glm::dvec3& v : m.vertices) out.print("v %.9g %.9g %.9g\n", v.x, v.y, v.z);
        for (const glm::dvec3& n : normals) {
            const double len = glm::length(n);
            const glm::dvec3 u = len > 0 ? n / len : glm::dvec3(0);
            out.print("vn %.6f %.6f %.6f\n", u.x, u.y, u.z);
        }
        for (const auto& t : m.triangles) {
            const size_t a = base + t[0], b = base + t[1], c = base + t[2];
            out.print("f %zu//%zu %zu//%zu %zu//%zu\n", a, a, b, b, c, c);
        }
        base += m.vertices.size();
    }
    out.commit();
}

}  // namespace cloth
