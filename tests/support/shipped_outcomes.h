// The outcomes of the shipped collider scenes (docs/colliders.md §10) that the CPU and GPU tests
// measure alike (tests/scene/shipped_scenes_test.cpp, tests/gpu/gpu_shipped_scenes_test.cpp), each
// on its own backend's solver: how close any vertex is to a collider, where the tablecloth's
// centre and lowest vertex end, how far the windsock is blown along the wind, where the cape's
// hem hangs in the turning figure's frame, and how the real-time sheet lands on its sphere.
#pragma once

#include <algorithm>
#include <glm/glm.hpp>
#include <string>
#include <variant>
#include <vector>

#include "model/collider_contact.h"
#include "model/collider_motion.h"
#include "model/collider_pose.h"
#include "model/scene.h"
#include "solver/diagnostics.h"
#include "solver/solver.h"

namespace cloth::test {

// φ − h of collider c at time t at p (docs/colliders.md §1–3): ≥ 0 outside its offset surface.
inline double clearance(const Collider& c, double t, const glm::dvec3& p) {
    const ShapeD shape = posedShape(c, t);
    return std::visit([&](const auto& s) { return contact(s, p).phi; }, shape) - c.thickness;
}

// The smallest clearance of any vertex from any collider at the solver's time.
inline double worstClearance(const Scene& scene, const Solver& solver) {
    double worst = 1e300;
    const SimState s = solver.read();
    for (const Collider& c : scene.colliders)
        for (const glm::dvec3& p : s.positions)
            worst = std::min(worst, clearance(c, solver.time(), p));
    return worst;
}

// The vertex in the middle of the cloth.
inline glm::dvec3 clothCentre(const Scene& scene, const SimState& s) {
    const Grid g = scene.grid();
    return s.positions[size_t(g.index(g.nu / 2, g.nv / 2))];
}

// The tablecloth at the solver's time: the table top (colliders[0]) and its height, the cloth's
// centre, its lowest vertex, and the worst clearance.
struct TableOutcome {
    Box top;
    double topY = 0;       // the top face's height [m]
    glm::dvec3 centre{0};  // [m]
    double lowest = 0;     // the lowest vertex's y [m]
    double clear = 0;      // worstClearance [m]
};
inline TableOutcome tableOutcome(const Scene& scene, const Solver& solver) {
    TableOutcome o;
    const SimState s = solver.read();
    o.top = *scene.colliders[0].as<Box>();
    o.topY = o.top.center.y + o.top.halfExtents.y;
    o.centre = clothCentre(scene, s);
    o.lowest = 1e300;
    for (const glm::dvec3& p : s.positions) o.lowest = std::min(o.lowest, p.y);
    o.clear = worstClearance(scene, solver);
    return o;
}

// The mean of the points along the direction w.
inline double meanAlong(const std::vector<glm::dvec3>& xs, const glm::dvec3& w) {
    double sum = 0;
    for (const glm::dvec3& p : xs) sum += glm::dot(p, w);
    return sum / double(xs.size());
}

// The grid's rest positions, row by row.
inline std::vector<glm::dvec3> restPositions(const Grid& g) {
    std::vector<glm::dvec3> rest;
    for (int j = 0; j < g.nv; ++j)
        for (int i = 0; i < g.nu; ++i) rest.push_back(g.restPosition(i, j));
    return rest;
}

// How far the cloth of `solver` has moved along the wind of `scene` (its mean displacement along
// the wind's direction from the rest grid) [m]; `solver` may run the same scene without wind.
inline double shiftAlongWind(const Scene& scene, const Solver& solver) {
    const glm::dvec3 w = scene.wind->direction;
    return meanAlong(solver.read().positions, w) - meanAlong(restPositions(scene.grid()), w);
}

// The shift along the wind averaged over the frames (the scene's substeps) from `from` to `to`
// [s], and its least value there, stepping `solver` to `to`; `bad` gets the reason if a step
// went unstable. Once the sock flaps, its shift at one instant depends on every rounding (CPU
// float, double and two GPUs put it 0.1 m apart at 2 s); its mean over a second does not.
struct WindShift {
    double mean = 0, least = 1e300;
};
inline WindShift shiftAlongWindOver(const Scene& scene, Solver& solver, double from, double to,
                                    std::string& bad) {
    const long frame = std::max(1, scene.integrator.substeps);
    WindShift w;
    int frames = 0;
    while (solver.time() < to - 1e-9) {
        const StepResult r = solver.step(frame);
        if (r.unstable) {
            bad = r.reason;
            break;
        }
        if (solver.time() < from - 1e-9) continue;
        const double shift = shiftAlongWind(scene, solver);
        w.mean += shift;
        w.least = std::min(w.least, shift);
        ++frames;
    }
    w.mean /= std::max(frames, 1);
    return w;
}

// The middle of the cape's hem (its last row) at time t, turned back into the figure's rest frame
// (colliders[0]'s motion undone).
inline glm::dvec3 capeHemInFiguresFrame(const Scene& scene, const SimState& s, double t) {
    const Grid g = scene.grid();
    const Motion turn = scene.colliders[0].motion->motion();
    const glm::dvec3 hem = s.positions[size_t(g.index(g.nu / 2, g.nv - 1))];
    return glm::transpose(poseAt(turn, t).rotation) * hem;
}

// The real-time sheet (scenes/realtime.json) stepped frame by frame to `to` [s]: the most
// strained spring of any family at the end of any frame (the run's own check, max_strain, reads
// the same), and at the end the worst clearance, the highest vertex's height above the sphere's
// top (colliders[1], its shell at R + h) and the lowest vertex's height [m]; `bad` gets the
// reason if a step went unstable.
struct RealtimeOutcome {
    double worstStrain = 0, clear = 0, aboveTop = 0, lowest = 1e300;
};
inline RealtimeOutcome realtimeOutcome(const Scene& scene, Solver& solver, double to,
                                       std::string& bad) {
    RealtimeOutcome o;
    const long frame = std::max(1, scene.integrator.substeps);
    while (solver.time() < to - 1e-9) {
        const StepResult r = solver.step(frame);
        if (r.unstable) {
            bad = r.reason;
            break;
        }
        o.worstStrain = std::max(o.worstStrain, largestStrain(scene, solver.read()).strain);
    }
    const SimState s = solver.read();
    const Sphere& ball = *scene.colliders[1].as<Sphere>();
    double highest = -1e300;
    for (const glm::dvec3& p : s.positions) {
        highest = std::max(highest, p.y);
        o.lowest = std::min(o.lowest, p.y);
    }
    o.aboveTop = highest - (ball.center.y + ball.radius + scene.colliders[1].thickness);
    o.clear = worstClearance(scene, solver);
    return o;
}

}  // namespace cloth::test
