// Every key in its range does not make every quantity computed from the keys a double: 1e308 N/m
// is a valid stiffness, but the stability bound adds eight of them. Each quantity the model,
// `validate` and the diagnostics derive from the scene at rest is bounded here, in one place,
// once the scene is built, and must be finite (and a spacing non-zero); otherwise the key that
// pushed it over is named, instead of a bound of inf or nan or a run that fails as "unstable".
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <variant>

#include "model/stability.h"
#include "scene/scene_reader.h"

namespace cloth::detail {
namespace {

// One factor of a derived quantity: the key it comes from and its size in the product.
struct Factor {
    const char* key;
    double size;
};

// The factor furthest from 1 in a product that overflows is the one that pushed it over.
const char* culprit(std::initializer_list<Factor> factors) {
    auto distance = [](double size) { return size > 0 ? std::abs(std::log(size)) : 0.0; };
    const Factor* worst = factors.begin();
    for (const Factor& f : factors)
        if (distance(f.size) > distance(worst->size)) worst = &f;
    return worst->key;
}

// The stiffest declared family: the one that dominates the stability bound.
const char* stiffestFamily(const SpringStiffness& k) {
    if (k.structural >= k.shear && k.structural >= k.bend) return "springs.structural";
    return k.shear >= k.bend ? "springs.shear" : "springs.bend";
}

}  // namespace

void SceneReader::checkDerivedFinite(const Scene& s) const {
    auto expect = [&](double value, std::initializer_list<Factor> factors, const char* what) {
        if (!std::isfinite(value)) fail(culprit(factors), std::string(what) + " overflows");
    };
    const Grid g = s.grid();

    // The grid: spacing, rest lengths (the spring code takes |d|, which squares d), extent and
    // rest positions. Only the families the scene models have springs to measure.
    for (int slot = 0; slot < 12; ++slot) {
        const SpringOffset& o = kSpringOffsets[std::size_t(slot)];
        if (s.slotStiffness(slot) <= 0 || std::abs(o.di) >= g.nu || std::abs(o.dj) >= g.nv)
            continue;
        const double rest = g.restLength(o.di, o.dj);
        char what[96];
        std::snprintf(what, sizeof what, "the rest length of the %s springs", familyName(o.family));
        expect(rest, {{"cloth.size", 2}}, what);
        if (!(rest > 0))
            fail("cloth.size", std::string(what) + " underflows to 0 (size/(n-1) is too small)");
    }
    if ((g.nu > 1 && !(g.du > 0)) || (g.nv > 1 && !(g.dv > 0)))
        fail("cloth.size", "the grid spacing size/(n-1) underflows to 0");
    const double extent = g.extent();
    expect(extent, {{"cloth.size", 2}}, "the cloth's extent |size|");
    expect(glm::length(g.origin), {{"cloth.origin", 2}}, "|origin|");
    double reach = 0;  // the largest |rest position|: the corners bound every vertex
    for (int j : {0, g.nv - 1})
        for (int i : {0, g.nu - 1}) reach = std::max(reach, glm::length(g.restPosition(i, j)));
    expect(reach, {{"cloth.origin", 2}},
           "the largest rest position |origin + size| (cloth.size added)");

    // A material's lattice (docs/physics.md): the shear springs add G·du²/dv² to the stiffness
    // along u, which the structural springs must not have to cancel with a negative K.
    if (s.material) {
        const MembraneSprings k = membraneSprings(*s.material, g.du, g.dv);
        expect(k.alongU + k.alongV + k.shear,
               {{"material.stretch", s.material->stretch}, {"material.shear", s.material->shear}},
               "the lattice's spring stiffness");
        if (k.alongU < 0 || k.alongV < 0) {
            char buf[300];
            std::snprintf(buf, sizeof buf,
                          "shear %g N/m is too stiff for stretch %g N/m on cells of %g x %g m: the "
                          "springs along %s would need a negative stiffness (shear must be at most "
                          "about stretch·min(du,dv)²/max(du,dv)²)",
                          s.material->shear, s.material->stretch, g.du, g.dv,
                          k.alongU < 0 ? "u" : "v");
            fail("material.shear", buf);
        }
    }

    // Mass: the integrators divide by it; the lightest vertex (a corner with a material) is the
    // one that matters.
    const char* massKey = s.material ? "material.density" : "cloth.mass";
    const double m = s.material ? s.vertexMass(0, 0) : s.cloth.mass, inverseMass = 1 / m;
    expect(m, {{massKey, m}}, "the vertex mass");
    if (!(m > 0)) fail(massKey, "the lightest vertex's mass underflows to 0");
    expect(inverseMass, {{massKey, inverseMass}}, "the inverse mass 1/m");

    // Gravity: its magnitude, the weight m·g, one step's g·dt² and the potential energy at rest
    // Σ m g·x that the diagnostics report.
    const double gravity = glm::length(s.gravity), dt = s.integrator.dt;
    expect(gravity, {{"gravity", 2}}, "|gravity|");
    expect(m * gravity, {{massKey, m}, {"gravity", gravity}}, "the weight m·|gravity|");
    expect(gravity * dt * dt, {{"gravity", gravity}, {"integrator.dt", dt * dt}},
           "one step's |gravity|·dt²");
    const double count = double(g.count());
    expect(count * m * gravity * reach,
           {{massKey, m},
            {"gravity", gravity},
            {extent > glm::length(g.origin) ? "cloth.size" : "cloth.origin", reach},
            {"cloth.resolution", count}},
           "the potential energy at rest Σ m·|gravity|·|x|");

    // The stability bound (model/stability.h). Gershgorin's row sum is at most 2·ΣK (12
    // neighbours, the off-diagonal counted twice), so bounding that bounds λ_max for any grid
    // and pins; validate's power estimate squares it, the integrators divide it by m and
    // multiply it by dt².
    const char* family = s.material ? (s.material->stretch >= s.material->shear ? "material.stretch"
                                                                                : "material.shear")
                                    : stiffestFamily(s.springs);
    double lambda = 0;  // 2·ΣK over the 12 slots: 8·(structural + shear + bend) per family
    for (int slot = 0; slot < 12; ++slot) lambda += 2 * s.slotStiffness(slot);
    expect(lambda, {{family, 2}}, "the stability bound lambda_max <= 8·(structural+shear+bend)");
    expect(lambda * lambda, {{family, 2}}, "lambda_max² (the stability estimate squares it)");
    const double w2 = lambda / m, c = s.dampingRate();
    const char* dampingKey = s.material ? "material.air_damping" : "damping";
    expect(w2, {{family, lambda}, {massKey, inverseMass}}, "the stability bound's lambda_max/m");
    expect(w2 * dt * dt, {{family, w2}, {"integrator.dt", dt * dt}},
           "the stiffness per step lambda_max·dt²/m");
    expect(c, {{dampingKey, c}, {massKey, inverseMass}}, "the damping rate c");
    expect(c * c + 4 * w2, {{dampingKey, c}, {family, std::sqrt(4 * w2)}},
           "the symplectic Euler stability bound's (damping/m)² + 4·lambda_max/m");
    if (const double beta = s.springDamping(); beta > 0) {  // docs/stability.md "Spring damping"
        expect(beta * w2, {{"material.spring_damping", beta}, {family, w2}},
               "the spring damping's rate beta·lambda_max/m");
        expect(beta * w2 * dt, {{"material.spring_damping", beta * w2}, {"integrator.dt", dt}},
               "the spring damping per step beta·lambda_max·dt/m");
    }
    for (Method method : kMethods)
        if (std::isnan(methodDt(method, lambda, m, c * m)))
            fail(family,
                 std::string("the stability bound of ") + methodName(method) + " is not a number");

    // Wind: its acceleration K_w/m.
    if (s.wind) {
        const double strength = std::abs(s.wind->strength);
        expect(strength * inverseMass, {{"wind.strength", strength}, {massKey, inverseMass}},
               "the wind's acceleration |strength|/m");
    }

    // Colliders: the contact tests square a distance as far as the shape reaches, where it sits
    // plus its size plus its thickness.
    for (std::size_t n = 0; n < s.colliders.size(); ++n) {
        const Collider& collider = s.colliders[n];
        const std::string at = "colliders[" + std::to_string(n) + "].";
        std::string whereKey = at, sizeKey = at;
        double where = 0, size = 0;
        if (const auto* p = std::get_if<Plane>(&collider.shape)) {
            whereKey += "point", where = glm::length(p->point);
        } else if (const auto* sp = std::get_if<Sphere>(&collider.shape)) {
            whereKey += "center", where = glm::length(sp->center);
            sizeKey += "radius", size = sp->radius;
        } else if (const auto* b = std::get_if<Box>(&collider.shape)) {
            whereKey += "center", where = glm::length(b->center);
            sizeKey += "half_extents", size = glm::length(b->halfExtents);
        } else if (const auto* cap = std::get_if<Capsule>(&collider.shape)) {
            whereKey += "a", where = std::max(glm::length(cap->a), glm::length(cap->b));
            sizeKey += "radius", size = cap->radius;
        } else if (const auto* mesh = std::get_if<MeshCollider>(&collider.shape)) {
            whereKey += "translation", where = glm::length(mesh->translation);
            sizeKey += "band", size = mesh->band;
        }
        const std::string thicknessKey = at + "thickness";
        const double span = where + size + collider.thickness;
        expect(
            span * span,
            {{whereKey.c_str(), where},
             {sizeKey.c_str(), size},
             {thicknessKey.c_str(), collider.thickness}},
            "the collider's reach² (|position| + size + thickness, squared by the contact test)");
    }

    // The instability test compares speed² with max_speed², and a step moves max_speed·dt.
    expect(s.maxSpeed * s.maxSpeed, {{"max_speed", 2}},
           "max_speed² (the instability test compares speed² with it)");
}

}  // namespace cloth::detail
