// `clothsim bench speed --peer bullet`: the same hanging cloth simulated by another library in
// the same process run, timed beside ours. The library code lives in bench_peer_bullet.cpp,
// built only when CMake finds Debian's libbullet-dev (CLOTH_HAVE_BULLET); this header and
// bench_peer.cpp are always built, so a build without Bullet can say why there is no peer.
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model/scene.h"

namespace cloth::app {

// Above this side the peer is not run (a 1024² btSoftBody takes seconds per step to build).
inline constexpr int kPeerMaxSide = 512;

// A cloth simulated by a peer library: the scene's grid, springs, mass, damping, gravity, pins
// and dt mapped onto the library's own model (see describe()).
class PeerCloth {
public:
    virtual ~PeerCloth() = default;
    virtual void step(long n) = 0;  // n steps of the scene's dt, one library step each
    virtual std::vector<glm::dvec3> positions() const = 0;  // k = j·nu + i [m]
    // The model as run: version, solver iterations, the stiffness and damping mapping.
    virtual std::string describe() const = 0;
    virtual std::string method() const = 0;     // the CSV's method column, e.g. "pbd_1_iteration"
    virtual double bytesPerVertex() const = 0;  // what the library holds per node [B]
};

// Why `name` cannot run in this build (an unknown name, or Bullet not compiled in), or nothing.
std::optional<std::string> peerUnavailable(const std::string& name);

// The peer `name` on `scene` (peerUnavailable(name) must be empty).
std::unique_ptr<PeerCloth> makePeerCloth(const std::string& name, const Scene& scene);

// Bullet's link stiffness for a spring of stiffness K [N/m] between two nodes of mass m [kg] at
// step dt [s]: the fraction of a link's violation one position iteration removes that makes the
// link's impulse per step K·C·dt, as an explicit spring's (XPBD's compliance 1/K with one
// iteration: kLST = w K dt² / (1 + w K dt²), w = 2/m the pair's inverse mass).
inline double bulletLinkStiffness(double k, double mass, double dt) {
    const double a = (2 / mass) * k * dt * dt;
    return a / (1 + a);
}

// Bullet's damping kDP multiplies the velocity by (1 − kDP) each step; ours is −μv/m per unit
// time (DESIGN.md §2), so one step of dt removes μ·dt/m of it.
inline double bulletDamping(double mu, double mass, double dt) {
    return std::min(1.0, mu * dt / mass);
}

// A run exploded when a position is not finite or lies further than `extents` cloth extents
// from every start position's bounding box: then the reason, else nothing.
inline std::optional<std::string> peerExplosion(const std::vector<glm::dvec3>& start,
                                                const std::vector<glm::dvec3>& now, double extent,
                                                double extents = 5) {
    if (start.empty() || start.size() != now.size()) return "no positions to check";
    glm::dvec3 lo = start[0], hi = start[0];
    for (const glm::dvec3& p : start) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    const double reach = extents * extent;
    for (std::size_t k = 0; k < now.size(); ++k) {
        const glm::dvec3& p = now[k];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return "node " + std::to_string(k) + " is not finite";
        const glm::dvec3 out = glm::max(lo - p, p - hi);
        if (glm::max(out.x, glm::max(out.y, out.z)) > reach)
            return "node " + std::to_string(k) + " is more than " + std::to_string(extents) +
                   " cloth extents from where the cloth started";
    }
    return std::nullopt;
}

// A run in which no node moved at all: under gravity a sign that the library froze the cloth
// (asleep, or steps too small for its precision), which would look fast.
inline bool peerFrozen(const std::vector<glm::dvec3>& start, const std::vector<glm::dvec3>& now) {
    return start == now;
}

}  // namespace cloth::app
