// Mesh → SDF baking (docs/colliders.md §4): the baked grid of a closed mesh agrees with the exact
// SDF of the shape it approximates within the bound (√3/2)·cell + ε_mesh (trilinear
// interpolation of a 1-Lipschitz field, plus how far the mesh is from the shape); its gradient
// is the shape's normal; bad meshes are refused naming the file and the first bad edge.
#include "model/mesh_sdf.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>

#include "model/collider_mesh.h"
#include "model/errors.h"
#include "reference/reference_colliders.h"
#include "support/draws.h"
#include "support/process.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
using D3 = glm::dvec3;

std::string tempObj(const std::string& name) {
    return (test::testTempDir() / name).string();
}

// The test's own OBJ writer: `v` lines and 1-based `f` lines, nothing else.
std::string writeObjText(const std::string& name, const TriMesh& m) {
    const std::string path = tempObj(name);
    std::ofstream out(path);
    out.precision(17);
    for (const D3& v : m.vertices) out << "v " << v.x << " " << v.y << " " << v.z << "\n";
    for (const auto& t : m.triangles)
        out << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
    return path;
}

std::string writeText(const std::string& name, const std::string& text) {
    const std::string path = tempObj(name);
    std::ofstream(path) << text;
    return path;
}

TriMesh unitBox() {
    return boxMesh({{0, 0, 0}, {0.5, 0.5, 0.5}, glm::dmat3(1)});
}

double analyticBox(const D3& p, const D3& c, const D3& h) {
    const D3 d = glm::abs(p - c) - h;
    return glm::length(glm::max(d, D3(0))) + std::min(std::max(d.x, std::max(d.y, d.z)), 0.0);
}

D3 randomIn(std::mt19937& rng, const SdfGrid& g) {
    std::uniform_real_distribution<double> u(0, 1);
    const D3 size = g.cell * D3(g.count - 1);
    return g.origin + test::drawVec3(u, rng) * size;
}

// Law: |φ_grid − φ_sphere| ≤ (√3/2)·cell + ε_mesh everywhere in the grid, with ε_mesh the largest
// gap between the icosphere and the sphere (at a face centre); the normal from the grid's
// gradient is within 2° more than the facets' own tilt of the radial direction near the surface.
TEST(MeshSdf, IcosphereAgreesWithTheAnalyticSphereWithinTheGridBound) {
    const SphereT<double> sphere{{0.1, -0.2, 0.3}, 0.5};
    const TriMesh mesh = loadObjMesh(writeObjText("ico.obj", sphereMesh(sphere, 3)));
    double epsMesh = 0;     // R − distance of the centre to the nearest face plane
    double facetAngle = 0;  // the largest angle between a face's normal and a radius to a corner
    for (const auto& t : mesh.triangles) {
        const D3 a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
        const D3 n = glm::normalize(glm::cross(b - a, c - a));
        epsMesh = std::max(epsMesh, sphere.radius - glm::dot(a - sphere.center, n));
        for (const D3& v : {a, b, c})
            facetAngle =
                std::max(facetAngle,
                         std::acos(std::min(1.0, glm::dot(n, glm::normalize(v - sphere.center)))));
    }
    const double cell = 0.05;
    const auto start = std::chrono::steady_clock::now();
    const SdfGrid g = bakeSdf(mesh, cell, 0.1);
    const double bakeSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const SdfColliderT<double> sdf{&g};
    const double bound = std::sqrt(3.0) / 2 * cell + epsMesh;
    std::mt19937 rng(1);
    double worst = 0, worstNear = 0, worstAngle = 0;
    for (int k = 0; k < 20000; ++k) {
        const D3 p = randomIn(rng, g);
        const D3 r = p - sphere.center;
        const double exact = glm::length(r) - sphere.radius;
        const ContactT<double> c = contact(sdf, p);
        worst = std::max(worst, std::abs(c.phi - exact));
        if (std::abs(exact) < 2 * cell) {
            worstNear = std::max(worstNear, std::abs(c.phi - exact));
            worstAngle = std::max(worstAngle,
                                  std::acos(std::min(1.0, glm::dot(c.normal, glm::normalize(r)))));
        }
    }
    EXPECT_LE(worst, bound);
    EXPECT_LE(worstNear, 0.25 * cell + epsMesh);  // near the surface the field is nearly affine
    // The mesh's own normals are off the radius by up to facetAngle; the grid adds a little.
    EXPECT_LE(worstAngle, facetAngle + 2 * std::numbers::pi / 180);
    std::printf(
        "icosphere R %.2f, cell %.3f: ε_mesh %.4f, max |error| %.4f (bound %.4f), within "
        "2 cells of the surface %.4f, normal within %.2f° (facets %.2f°)\n",
        sphere.radius, cell, epsMesh, worst, bound, worstNear, worstAngle * 180 / std::numbers::pi,
        facetAngle * 180 / std::numbers::pi);
    std::printf("baked %zu triangles into %d x %d x %d samples in %.3f s\n", mesh.triangles.size(),
                g.count.x, g.count.y, g.count.z, bakeSeconds);
}

// Law: a box mesh is the box exactly (ε_mesh = 0), so |φ_grid − φ_box| ≤ (√3/2)·cell, and in a
// cell whose eight corners all see the same face the field is affine, so the grid's gradient is
// that face's normal to rounding.
TEST(MeshSdf, BoxMeshAgreesWithTheAnalyticBoxAndItsFaceNormals) {
    const D3 c(0.2, 0.1, -0.1), h(0.3, 0.2, 0.4);
    const TriMesh mesh = loadObjMesh(writeObjText("box.obj", boxMesh({c, h, glm::dmat3(1)})));
    const double cell = 0.04;
    const SdfGrid g = bakeSdf(mesh, cell, 0.12);
    const SdfColliderT<double> sdf{&g};
    std::mt19937 rng(4);
    double worst = 0, worstNormal = 0;
    int faceCells = 0;
    for (int k = 0; k < 20000; ++k) {
        const D3 p = randomIn(rng, g);
        const ContactT<double> got = contact(sdf, p);
        worst = std::max(worst, std::abs(got.phi - analyticBox(p, c, h)));
        // The analytic box's normal at the 8 corners of p's cell.
        const D3 u = (p - g.origin) / g.cell;
        const D3 base = g.origin + g.cell * glm::min(glm::floor(u), D3(g.count - 2));
        const BoxT<double> box{c, h, glm::dmat3(1)};
        const D3 n0 = contact(box, base).normal;
        bool oneFace = contact(box, base).phi > 0 && glm::length(n0 - glm::round(n0)) == 0;
        for (int corner = 1; corner < 8 && oneFace; ++corner) {
            const D3 q = base + g.cell * D3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
            const ContactT<double> cq = contact(box, q);
            oneFace = cq.phi > 0 && glm::length(cq.normal - n0) == 0;
        }
        if (!oneFace) continue;
        ++faceCells;
        worstNormal = std::max(worstNormal, glm::length(got.normal - n0));
    }
    EXPECT_LE(worst, std::sqrt(3.0) / 2 * cell);
    EXPECT_GT(faceCells, 1000);
    EXPECT_LE(worstNormal, 1e-9);
    std::printf(
        "box mesh, cell %.3f: max |error| %.5f (bound %.5f); face-region normals within "
        "%.2g over %d samples\n",
        cell, worst, std::sqrt(3.0) / 2 * cell, worstNormal, faceCells);
}

// Every sample of `g` (or `samples` random ones) against brute force over all triangles with
// the reference's own point–triangle distance, the sign from the winding number at that sample.
void expectExactSamples(const TriMesh& m, const SdfGrid& g, int samples) {
    std::mt19937 rng(8);
    const int all = g.count.x * g.count.y * g.count.z;
    int inside = 0;
    for (int n = 0; n < (samples > 0 ? samples : all); ++n) {
        const int at = samples > 0 ? int(rng() % unsigned(all)) : n;
        const int i = at % g.count.x, j = at / g.count.x % g.count.y,
                  k = at / (g.count.x * g.count.y);
        const D3 p = g.origin + g.cell * D3(i, j, k);
        double d = INFINITY;
        const auto r = [&](std::uint32_t v) {
            return ref::V3{m.vertices[v].x, m.vertices[v].y, m.vertices[v].z};
        };
        for (const auto& t : m.triangles)
            d = std::min(d, ref::triangleDistance({p.x, p.y, p.z}, r(t[0]), r(t[1]), r(t[2])));
        const bool in = std::abs(windingNumber(m, p)) > 0.5;
        inside += in && d > 0;
        ASSERT_NEAR(g.at(i, j, k), in ? -d : d, 1e-12) << i << " " << j << " " << k;
    }
    EXPECT_GT(inside, 20);
}

// Law: every baked sample is the exact signed distance (the bake skips far triangles and carries
// the sign along rows; this checks both shortcuts). The box's faces lie on grid planes, and rows
// run along faces exactly one cell away: the adversarial case for carrying signs.
TEST(MeshSdf, BakedSamplesAreTheExactSignedDistance) {
    const TriMesh sphere = sphereMesh({{0.05, 0, -0.02}, 0.3}, 2);
    expectExactSamples(sphere, bakeSdf(sphere, 0.045, 0.07), 400);
    const TriMesh box = boxMesh({{0.2, 0.1, -0.1}, {0.3, 0.2, 0.4}, glm::dmat3(1)});
    expectExactSamples(box, bakeSdf(box, 0.04, 0.12), 0);
}

// Law: the winding number is ±1 inside a closed mesh and 0 outside, whatever its orientation.
TEST(MeshSdf, WindingNumberIsOneInsideZeroOutside) {
    TriMesh m = unitBox();
    EXPECT_NEAR(windingNumber(m, D3(0.1, -0.2, 0.3)), 1, 1e-12);
    EXPECT_NEAR(windingNumber(m, D3(0.9, 0, 0)), 0, 1e-12);
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
    EXPECT_NEAR(windingNumber(m, D3(0.1, -0.2, 0.3)), -1, 1e-12);
}

// Law: vertices repeated per face (as many exporters write them) are welded into one.
TEST(MeshSdf, WeldsRepeatedVertices) {
    const TriMesh box = unitBox();
    std::string text;
    char line[128];
    for (const auto& t : box.triangles) {
        for (const auto v : t) {
            std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", box.vertices[v].x,
                          box.vertices[v].y, box.vertices[v].z);
            text += line;
        }
        text += "f -3 -2 -1\n";
    }
    const TriMesh m = loadObjMesh(writeText("split.obj", text));
    EXPECT_EQ(m.vertices.size(), 8u);
    EXPECT_EQ(m.triangles.size(), 12u);
}

InputError loadError(const std::string& path, const MeshSource& src = {}) {
    try {
        loadObjMesh(path, src);
    } catch (const InputError& e) {
        return e;
    }
    ADD_FAILURE() << "no InputError for " << path;
    return InputError("", "", "");
}

// Law: a missing, empty, open or non-manifold mesh is an InputError naming the file and reason.
TEST(MeshSdf, BadMeshesAreReportedWithTheFileAndTheFirstBadEdge) {
    EXPECT_NE(std::string(loadError(tempObj("missing.obj")).what()).find("missing.obj: no such"),
              std::string::npos);
    const InputError keyed = loadError(tempObj("missing.obj"), {"scene.json", "colliders[2].file"});
    EXPECT_EQ(keyed.file(), "scene.json");
    EXPECT_EQ(keyed.key(), "colliders[2].file");
    EXPECT_NE(keyed.reason().find("missing.obj"), std::string::npos);

    const std::string empty = writeText("empty.obj", "# nothing here\nv 0 0 0\n");
    EXPECT_NE(loadError(empty).reason().find("no triangles"), std::string::npos);

    TriMesh open = unitBox();
    open.triangles.pop_back();
    EXPECT_NE(loadError(writeObjText("open.obj", open)).reason().find("not closed"),
              std::string::npos);

    TriMesh flipped = unitBox();
    std::swap(flipped.triangles[3][1], flipped.triangles[3][2]);
    EXPECT_NE(loadError(writeObjText("flipped.obj", flipped)).reason().find("same direction"),
              std::string::npos);

    TriMesh fin = unitBox();  // a fin on the edge (0, 4): that edge is shared by four triangles
    fin.vertices.push_back({-2, 0, 0});
    fin.triangles.push_back({0, 4, 8});
    fin.triangles.push_back({4, 0, 8});
    const std::string finReason = loadError(writeObjText("fin.obj", fin)).reason();
    EXPECT_NE(finReason.find("edge ("), std::string::npos) << finReason;

    // A vertex line tinyobjloader would read as 0 where a number is not: the box with one
    // coordinate a word, or missing, is refused naming the line (it loaded as another shape).
    const std::string boxText = [] {
        std::string text;
        for (const auto& v : unitBox().vertices)
            text += "v " + std::to_string(v.x) + " " + std::to_string(v.y) + " " +
                    std::to_string(v.z) + "\n";
        for (const auto& t : unitBox().triangles)
            text += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " +
                    std::to_string(t[2] + 1) + "\n";
        return text;
    }();
    EXPECT_NO_THROW(loadObjMesh(writeText("box.obj", boxText)));
    for (const std::string bad : {"v 0 0 abc", "v 0 0", "v 0 nan 0"}) {
        const std::string reason = loadError(writeText("badv.obj", bad + "\n" + boxText)).reason();
        EXPECT_NE(reason.find("line 1: '" + bad + "': a vertex needs three finite numbers"),
                  std::string::npos)
            << reason;
    }
    EXPECT_NE(loadError(::testing::TempDir()).reason().find("not a regular file"),
              std::string::npos);
}

// Law: a grid of more than kMaxSdfSamples, a cell ≤ 0 or a negative band is an InputError
// naming the key it was given, before anything is allocated.
TEST(MeshSdf, ACellTooFineForMemoryOrNotPositiveIsAnInputError) {
    const TriMesh m = unitBox();
    EXPECT_THROW(bakeSdf(m, 1e-4, 0.1), InputError);
    EXPECT_THROW(bakeSdf(m, 0, 0.1), InputError);
    EXPECT_THROW(bakeSdf(m, 0.1, -1), InputError);
    try {
        bakeSdf(m, 1e-4, 0.1, {"s.json", "colliders[0].cell"});
    } catch (const InputError& e) {
        EXPECT_EQ(e.key(), "colliders[0].cell");
        EXPECT_NE(e.reason().find("too fine for memory"), std::string::npos);
    }
}

// Law: the trilinear field is within (√3/2)·cell of the mesh's distance, so a cell past half the
// mesh's largest extent (fewer than two cells across it) cannot give its shape: an InputError
// naming the key, with the cell that would; half the extent itself is still taken.
TEST(MeshSdf, ACellCoarserThanHalfTheMeshIsAnInputError) {
    const TriMesh m = unitBox();
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::dvec3& v : m.vertices) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    EXPECT_NO_THROW(bakeSdf(m, extent / 2, 0.1));
    try {
        bakeSdf(m, 10, 0.1, {"s.json", "colliders[0].cell"});
        ADD_FAILURE() << "a 10 m cell on a mesh of " << extent << " m was taken";
    } catch (const InputError& e) {
        EXPECT_EQ(e.key(), "colliders[0].cell");
        EXPECT_NE(e.reason().find("fewer than 2 cells across the mesh"), std::string::npos)
            << e.reason();
    }
}

}  // namespace
}  // namespace cloth
