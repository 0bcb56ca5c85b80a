// src's collider geometry and contact response (model/collider_shapes.h, collider_contact.h)
// against the independent reference of tests/reference/reference_colliders.h, written from
// docs/colliders.md alone: φ and n of the box, capsule and grid over random points inside,
// outside, near faces, edges and corners, in double and float; the response with thickness,
// friction and collider velocity.
#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "model/collider_contact.h"
#include "model/mesh_sdf.h"
#include "reference/reference_colliders.h"
#include "support/box_regions.h"
#include "support/draws.h"

namespace cloth {
namespace {

using D3 = glm::dvec3;

ref::V3 toRef(const D3& v) {
    return {v.x, v.y, v.z};
}
D3 fromRef(const ref::V3& v) {
    return {v[0], v[1], v[2]};
}

// Points spread around a shape of size ~1, with a third of them pulled to within 1e-3 of a
// target (a face, edge or corner point of the shape) to exercise the region boundaries.
struct Sampler {
    std::mt19937 rng{17};
    std::uniform_real_distribution<double> u{-1, 1};
    D3 any(double spread) { return spread * test::drawVec3(u, rng); }
    D3 near(const D3& target, double r) { return target + r * test::drawVec3(u, rng); }
};

// The tolerance float must meet: a few ulps of the coordinates' size.
constexpr double kFloatTol = 2e-6;

template <typename T>
void compare(const ContactT<T>& got, const ref::Contact& want, double tol, bool normal) {
    EXPECT_NEAR(double(got.phi), want.phi, tol);
    if (normal) {
        EXPECT_NEAR(glm::length(D3(got.normal) - fromRef(want.normal)), 0, 50 * tol);
    }
}

// Law: src's oriented-box φ equals the reference's to 1e-14 (double) / 2e-6 (float), and n too
// wherever n is unambiguous (off the medial surface and the region borders).
TEST(ColliderReference, BoxDistanceAndNormalMatchTheReference) {
    const ref::Box rb{{0.1, -0.3, 0.2}, {0.5, 0.2, 0.35}, {1, -0.5, 2}, 37};
    const D3 axis = glm::normalize(fromRef(rb.axis));
    const BoxT<double> bd{fromRef(rb.center), fromRef(rb.half),
                          axisAngle(axis, rb.degrees * std::numbers::pi / 180)};
    const BoxT<float> bf{glm::vec3(bd.center), glm::vec3(bd.halfExtents), glm::mat3(bd.rotation)};
    Sampler s;
    int checkedNormals = 0;
    for (int k = 0; k < 30000; ++k) {
        D3 p = s.any(1.2);
        if (k % 3 == 1) {  // near a corner or an edge midpoint
            const D3 sgn(s.u(s.rng) < 0 ? -1 : 1, s.u(s.rng) < 0 ? -1 : 1, k % 2 ? 0 : 1);
            p = s.near(bd.center + bd.rotation * (sgn * bd.halfExtents), 1e-3);
        }
        const ref::Contact want = ref::boxContact(rb, toRef(p));
        const bool normal = test::clearOfBoxKinks<double>(bd, p, 1e-9);
        checkedNormals += normal;
        compare(contact(bd, p), want, 1e-14, normal);
        compare(contact(bf, glm::vec3(p)), want, kFloatTol,
                test::clearOfBoxKinks<double>(bd, p, 1e-2));
    }
    EXPECT_GT(checkedNormals, 25000);
}

// Law: src's capsule φ and n equal the reference's, around the cylinder and both end caps.
TEST(ColliderReference, CapsuleDistanceAndNormalMatchTheReference) {
    const ref::Capsule rc{{-0.3, 0.1, 0.2}, {0.4, -0.2, -0.1}, 0.25};
    const CapsuleT<double> cd{fromRef(rc.a), fromRef(rc.b), rc.radius};
    const CapsuleT<float> cf{glm::vec3(cd.a), glm::vec3(cd.b), float(cd.radius)};
    Sampler s;
    for (int k = 0; k < 30000; ++k) {
        D3 p = s.any(1.0);
        if (k % 3 == 1) p = s.near(k % 2 ? cd.a : cd.b, 0.3);  // around the end caps
        const ref::Contact want = ref::capsuleContact(rc, toRef(p));
        compare(contact(cd, p), want, 1e-14, true);
        // Float normals only away from the axis, where n is well conditioned.
        compare(contact(cf, glm::vec3(p)), want, kFloatTol, want.phi + rc.radius > 1e-2);
    }
}

// Law: src's trilinear value and gradient direction equal the reference's, at grid nodes too.
TEST(ColliderReference, GridValueAndGradientMatchTheReference) {
    ref::Grid rg{{-0.4, -0.3, -0.5}, 0.07, {11, 9, 13}, {}};
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int n = 0; n < 11 * 9 * 13; ++n) rg.values.push_back(u(rng));
    SdfGrid g;
    g.origin = fromRef(rg.origin);
    g.cell = rg.cell;
    g.count = {rg.count[0], rg.count[1], rg.count[2]};
    g.values = rg.values;
    const SdfColliderT<double> cd{&g};
    const SdfColliderT<float> cf{&g};
    for (int k = 0; k < 30000; ++k) {
        std::uniform_real_distribution<double> w(0, 1);
        D3 p = g.origin + g.cell * D3(w(rng) * 10, w(rng) * 8, w(rng) * 12);
        if (k % 4 == 0) p = g.origin + g.cell * glm::floor((p - g.origin) / g.cell);  // a node
        const ref::Contact want = ref::gridContact(rg, toRef(p));
        compare(contact(cd, p), want, 1e-13, true);
        EXPECT_NEAR(double(contact(cf, glm::vec3(p)).phi), want.phi, 1e-5);
    }
}

// Law: the bake's point–triangle distance (Voronoi regions) equals the reference's (foot of
// the perpendicular, else the nearest edge).
TEST(ColliderReference, TriangleDistanceMatchesTheReference) {
    Sampler s;
    for (int k = 0; k < 20000; ++k) {
        const D3 a = s.any(1), b = s.any(1), c = s.any(1), p = s.any(1.5);
        if (glm::length(glm::cross(b - a, c - a)) < 1e-3) continue;
        EXPECT_NEAR(pointTriangleDistance(p, a, b, c),
                    ref::triangleDistance(toRef(p), toRef(a), toRef(b), toRef(c)), 1e-12);
    }
}

// The response with thickness, friction and a moving collider, on a box: p and v as the
// reference computes them from the same (φ, n), double and float.
TEST(ColliderReference, ContactResponseMatchesTheReference) {
    const ref::Box rb{{0, 0, 0}, {0.4, 0.3, 0.2}, {0, 1, 1}, 20};
    const BoxT<double> bd{D3(0), fromRef(rb.half),
                          axisAngle(glm::normalize(D3(0, 1, 1)), 20 * std::numbers::pi / 180)};
    Sampler s;
    int touched = 0;
    for (int k = 0; k < 20000; ++k) {
        const D3 p0 = s.any(0.6), v0 = s.any(2), vc = s.any(0.5);
        const double h = k % 5 == 0 ? 0 : 0.02, cf = (k % 4) * 0.3;
        ref::V3 rp = toRef(p0), rv = toRef(v0);
        const bool refTouched = ref::respond(ref::boxContact(rb, rp), h, cf, toRef(vc), rp, rv);
        D3 p = p0, v = v0;
        const bool srcTouched = collide(bd, ContactParamsT<double>{h, cf}, vc, p, v);
        ASSERT_EQ(srcTouched, refTouched) << k;
        touched += srcTouched;
        EXPECT_NEAR(glm::length(p - fromRef(rp)), 0, 1e-14);
        EXPECT_NEAR(glm::length(v - fromRef(rv)), 0, 1e-13);
        glm::vec3 pf(p0), vf(v0);
        const BoxT<float> bf{glm::vec3(0), glm::vec3(bd.halfExtents), glm::mat3(bd.rotation)};
        // Float may decide differently at the contact threshold or on the medial surface.
        if (std::abs(ref::boxContact(rb, toRef(p0)).phi - h) < 1e-5 ||
            !test::clearOfBoxKinks<double>(bd, p0, 1e-4))
            continue;
        collide(bf, ContactParamsT<float>{float(h), float(cf)}, glm::vec3(vc), pf, vf);
        EXPECT_NEAR(glm::length(D3(pf) - fromRef(rp)), 0, 1e-5);
        EXPECT_NEAR(glm::length(D3(vf) - fromRef(rv)), 0, 1e-4);
    }
    EXPECT_GT(touched, 2000);
}

// The plane and the sphere through the shared response too: the reference's generic
// p + (h − φ) n and the sphere's c + (R + h) n are the same point to rounding.
TEST(ColliderReference, PlaneAndSphereResponsesMatchTheReference) {
    const PlaneT<double> plane{{0, 0.1, 0}, glm::normalize(D3(0.3, 1, 0.2))};
    const SphereT<double> sphere{{0.1, 0, -0.1}, 0.45};
    Sampler s;
    for (int k = 0; k < 20000; ++k) {
        const D3 p0 = s.any(0.7), v0 = s.any(2), vc = s.any(0.5);
        const double h = k % 3 == 0 ? 0 : 0.01, cf = (k % 4) * 0.3;
        for (const bool isSphere : {false, true}) {
            ref::V3 rp = toRef(p0), rv = toRef(v0);
            const ContactT<double> c = isSphere ? contact(sphere, p0) : contact(plane, p0);
            const ref::Contact want =
                isSphere ? ref::sphereContact({toRef(sphere.center), sphere.radius}, toRef(p0))
                         : ref::planeContact({toRef(plane.point), toRef(plane.normal)}, toRef(p0));
            EXPECT_NEAR(c.phi, want.phi, 1e-15);
            const bool refTouched = ref::respond(want, h, cf, toRef(vc), rp, rv);
            D3 p = p0, v = v0;
            const ContactParamsT<double> params{h, cf};
            const bool srcTouched =
                isSphere ? collide(sphere, params, vc, p, v) : collide(plane, params, vc, p, v);
            ASSERT_EQ(srcTouched, refTouched);
            EXPECT_NEAR(glm::length(p - fromRef(rp)), 0, 1e-14);
            EXPECT_NEAR(glm::length(v - fromRef(rv)), 0, 1e-13);
        }
    }
}

}  // namespace
}  // namespace cloth
