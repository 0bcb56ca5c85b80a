// The shared contact response of docs/colliders.md §2: DESIGN.md §2's rule bit for bit when
// thickness, friction and collider velocity are zero; the vertex ends at φ = h; the normal part
// of the relative velocity is removed; Coulomb friction takes at most c_f·|w_n|, static when it
// would reverse; a cloth vertex holds on a slope iff tan θ ≤ c_f.
#include "model/collider_contact.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <numbers>
#include <random>

#include "support/draws.h"

namespace cloth {
namespace {

using D3 = glm::dvec3;

template <typename T>
bool sameBits(const Vec3<T>& a, const Vec3<T>& b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

// DESIGN.md §2's rules as the spec writes them. Plane: s = ⟨p − c, n̂⟩; if s < 0, p ← p − s n̂ and
// v ← v − ⟨v, n̂⟩ n̂. Sphere: r = p − c; if |r| < R, n̂ = r/|r| ((0, 1, 0) at the centre),
// p ← c + R n̂, v ← v − ⟨v, n̂⟩ n̂.
template <typename T>
void seedRule(const PlaneT<T>& plane, Vec3<T>& p, Vec3<T>& v) {
    const T s = glm::dot(p - plane.point, plane.normal);
    if (s < T(0)) {
        p -= s * plane.normal;
        v -= glm::dot(v, plane.normal) * plane.normal;
    }
}
template <typename T>
void seedRule(const SphereT<T>& sphere, Vec3<T>& p, Vec3<T>& v) {
    const Vec3<T> r = p - sphere.center;
    const T len = glm::length(r);
    if (len < sphere.radius) {
        const Vec3<T> n = len > T(0) ? r / len : Vec3<T>(0, 1, 0);
        p = sphere.center + sphere.radius * n;
        v -= glm::dot(v, n) * n;
    }
}

// Law: with h = 0, c_f = 0 and v_c = 0 the one contact response both backends use is DESIGN.md
// §2's rule to the bit, for points inside, outside and on either side of the surface, in float
// and double.
template <typename T>
void expectSeedRuleBitForBit() {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    const PlaneT<T> plane{Vec3<T>(T(0.1), T(-0.2), T(0.3)),
                          Vec3<T>(glm::normalize(D3(0.2, 1, -0.3)))};
    const SphereT<T> sphere{Vec3<T>(T(0.2), T(0.1), T(-0.1)), T(0.7)};
    const ContactParamsT<T> none;
    int touched = 0;
    for (int k = 0; k < 20000; ++k) {
        const Vec3<T> p0(test::drawVec3(u, rng)), v0(test::drawVec3(u, rng));
        Vec3<T> pa = p0, va = v0, pb = p0, vb = v0;
        seedRule(plane, pa, va);
        touched += collide(plane, none, Vec3<T>(0), pb, vb);
        ASSERT_TRUE(sameBits(pa, pb) && sameBits(va, vb)) << "plane, sample " << k;
        pa = pb = p0;
        va = vb = v0;
        seedRule(sphere, pa, va);
        touched += collide(sphere, none, Vec3<T>(0), pb, vb);
        ASSERT_TRUE(sameBits(pa, pb) && sameBits(va, vb)) << "sphere, sample " << k;
    }
    EXPECT_GT(touched, 5000);  // both branches were taken
}

TEST(ContactResponse, ZeroThicknessFrictionAndSpeedIsTheSeedRuleBitForBitDouble) {
    expectSeedRuleBitForBit<double>();
}
TEST(ContactResponse, ZeroThicknessFrictionAndSpeedIsTheSeedRuleBitForBitFloat) {
    expectSeedRuleBitForBit<float>();
}

// Law: after the response the vertex is at φ = h and its velocity relative to the collider has
// no normal part; the tangential part lost exactly min(|w_t|, c_f |w_n|).
TEST(ContactResponse, EndsAtTheThicknessWithNoRelativeNormalSpeedAndCoulombLoss) {
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> u(-1, 1);
    const CapsuleT<double> cap{{0, 0, 0}, {0.5, 0.2, 0}, 0.4};
    const ContactParamsT<double> params{0.01, 0.6};
    int statics = 0, kinetics = 0;
    for (int k = 0; k < 5000; ++k) {
        D3 p = 0.5 * test::drawVec3(u, rng), v = test::drawVec3(u, rng);
        const D3 vc = 0.3 * test::drawVec3(u, rng);
        const ContactT<double> before = contact(cap, p);
        const D3 w = v - vc;
        const double wn = glm::dot(w, before.normal);
        const double wt = glm::length(w - wn * before.normal);
        if (!collide(cap, params, vc, p, v)) continue;
        EXPECT_NEAR(contact(cap, p).phi, params.thickness, 1e-12);
        const D3 after = v - vc;
        EXPECT_NEAR(glm::dot(after, before.normal), 0, 1e-12);
        const double lost = wt - glm::length(after);
        EXPECT_NEAR(lost, std::min(wt, params.friction * std::abs(wn)), 1e-12);
        (wt <= params.friction * std::abs(wn) ? statics : kinetics)++;
    }
    EXPECT_GT(statics, 100);
    EXPECT_GT(kinetics, 100);
}

// Law: static friction carries the vertex with the collider (v = v_c exactly); a frictionless
// contact with a moving collider keeps the tangential slip and takes the collider's normal speed.
TEST(ContactResponse, StaticFrictionCarriesTheVertexWithTheCollider) {
    const PlaneT<double> floor{{0, 0, 0}, {0, 1, 0}};
    const D3 vc(0.5, 0.2, 0);  // a floor moving sideways and up
    D3 p(0, -0.001, 0), v(0, -1, 0);
    collide(floor, ContactParamsT<double>{0, 1.0}, vc, p, v);
    EXPECT_EQ(v, vc);
    p = {0, -0.001, 0};
    v = {0, -1, 0};
    collide(floor, ContactParamsT<double>{}, vc, p, v);
    EXPECT_NEAR(glm::length(v - D3(0, 0.2, 0)), 0, 1e-15);  // slip −0.5 kept, normal speed 0.2
}

// One vertex on a slope of angle θ under gravity, explicit Euler (DESIGN.md §2, positions with
// the old velocity), then the contact: how far it slid along the slope in `seconds`.
double slideDistance(double thetaDeg, double friction, double dt, double seconds) {
    const double th = thetaDeg * std::numbers::pi / 180;
    const PlaneT<double> slope{{0, 0, 0}, {-std::sin(th), std::cos(th), 0}};
    const D3 g(0, -9.81, 0), down(std::cos(th), std::sin(th), 0);  // down-slope is −down
    D3 p(0, 0, 0), v(0);
    const ContactParamsT<double> params{0.002, friction};
    for (int s = 0; s < int(seconds / dt); ++s) {
        const D3 vOld = v;
        v += dt * g;
        p += dt * vOld;
        collide(slope, params, D3(0), p, v);
    }
    return -glm::dot(p, down);
}

// Law (docs/colliders.md §2): at rest, gravity brings w_n = g cos θ Δt into the contact each step
// and a tangential g sin θ Δt, so the vertex holds iff tan θ ≤ c_f. The sliding threshold found
// by bisection is within a few degrees (here 0.5°) of atan(c_f).
TEST(ContactResponse, HoldsOnASlopeBelowTheFrictionAngleAndSlidesAbove) {
    for (const double friction : {0.2, 0.5, 1.0}) {
        const double critical = std::atan(friction) * 180 / std::numbers::pi;
        const auto slides = [&](double deg) {
            return slideDistance(deg, friction, 1e-3, 2) > 0.05;
        };
        EXPECT_FALSE(slides(critical - 2)) << "c_f " << friction;
        EXPECT_TRUE(slides(critical + 2)) << "c_f " << friction;
        double lo = 0, hi = 89;
        for (int it = 0; it < 30; ++it) (slides(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
        EXPECT_NEAR(lo, critical, 0.5) << "c_f " << friction;
        std::printf("c_f %.1f: slides above %.3f°, atan(c_f) = %.3f°\n", friction, lo, critical);
    }
}

}  // namespace
}  // namespace cloth
