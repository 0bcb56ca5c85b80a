// Every key in its range does not make every quantity computed from the keys a double: 1e308 N/m
// is a valid stiffness, but the stability bound adds eight of them. Each quantity the model,
// `validate` and the diagnostics derive from the scene at rest is bounded here, in one place,
// once the scene is built, and must be finite (and a spacing non-zero); otherwise the key that
// pushed it over is named, instead of a bound of inf or nan or a run that fails as "unstable".
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>

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
    for (const SpringOffset& o : kSpringOffsets) {
        if (s.springs.of(o.family) <= 0 || std::abs(o.di) >= g.nu || std::abs(o.dj) >= g.nv)
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

    // Mass: the integrators divide by it.
    const double m = s.cloth.mass, inverseMass = 1 / m;
    expect(inverseMass, {{"cloth.mass", inverseMass}}, "the inverse mass 1/m");

    // Gravity: its magnitude, the weight m·g, one step's g·dt² and the potential energy at rest
    // Σ m g·x that the diagnostics report.
    const double gravity = glm::length(s.gravity), dt = s.integrator.dt;
    expect(gravity, {{"gravity", 2}}, "|gravity|");
    expect(m * gravity, {{"cloth.mass", m}, {"gravity", gravity}}, "the weight m·|gravity|");
    expect(gravity * dt * dt, {{"gravity", gravity}, {"integrator.dt", dt * dt}},
           "one step's |gravity|·dt²");
    const double count = double(g.count());
    expect(count * m * gravity * reach,
           {{"cloth.mass", m},
            {"gravity", gravity},
            {extent > glm::length(g.origin) ? "cloth.size" : "cloth.origin", reach},
            {"cloth.resolution", count}},
           "the potential energy at rest Σ m·|gravity|·|x|");

    // The stability bound (model/stability.h). Gershgorin's row sum is at most 8·ΣK (12
    // neighbours, the off-diagonal counted twice), so bounding that bounds λ_max for any grid
    // and pins; validate's power estimate squares it, the integrators divide it by m and
    // multiply it by dt².
    const SpringStiffness& k = s.springs;
    const char* family = stiffestFamily(k);
    const double lambda = 8 * (k.structural + k.shear + k.bend);
    expect(lambda, {{family, 2}}, "the stability bound lambda_max <= 8·(structural+shear+bend)");
    expect(lambda * lambda, {{family, 2}}, "lambda_max² (the stability estimate squares it)");
    const double w2 = lambda / m, c = s.damping / m;
    expect(w2, {{family, lambda}, {"cloth.mass", inverseMass}},
           "the stability bound's lambda_max/m");
    expect(w2 * dt * dt, {{family, w2}, {"integrator.dt", dt * dt}},
           "the stiffness per step lambda_max·dt²/m");
    expect(c, {{"damping", s.damping}, {"cloth.mass", inverseMass}}, "the damping rate damping/m");
    expect(c * c + 4 * w2, {{"damping", c}, {family, std::sqrt(4 * w2)}},
           "the symplectic Euler stability bound's (damping/m)² + 4·lambda_max/m");
    for (Method method : kMethods)
        if (std::isnan(methodDt(method, lambda, m, s.damping)))
            fail(family,
                 std::string("the stability bound of ") + methodName(method) + " is not a number");

    // Wind: its acceleration K_w/m.
    if (s.wind) {
        const double strength = std::abs(s.wind->strength);
        expect(strength * inverseMass, {{"wind.strength", strength}, {"cloth.mass", inverseMass}},
               "the wind's acceleration |strength|/m");
    }

    // The instability test compares speed² with max_speed², and a step moves max_speed·dt.
    expect(s.maxSpeed * s.maxSpeed, {{"max_speed", 2}},
           "max_speed² (the instability test compares speed² with it)");
}

}  // namespace cloth::detail
