// Runs a solver and checks its frames with the independent self-intersection checker
// (tests/reference/self_intersection.h): the CPU and GPU self-collision tests share it.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>

#include "reference/self_intersection.h"
#include "solver/solver.h"

namespace cloth::test {

// The state as a triangle mesh, triangulated as the OBJ writer does (docs/physics.md): quad
// (i, j) is (a, b, c) and (a, c, d), a = (i, j), b = (i+1, j), c = (i+1, j+1), d = (i, j+1).
inline ref::TriangleMesh meshOf(const SimState& s) {
    ref::TriangleMesh m;
    for (const glm::dvec3& p : s.positions) m.positions.push_back({p.x, p.y, p.z});
    for (int j = 0; j + 1 < s.nv; ++j)
        for (int i = 0; i + 1 < s.nu; ++i) {
            const int a = j * s.nu + i, b = a + 1, c = a + s.nu + 1, d = a + s.nu;
            m.triangles.push_back({a, b, c});
            m.triangles.push_back({a, c, d});
        }
    return m;
}

struct SelfCheck {
    long worstCrossings = 0;  // most edge–triangle crossings in one checked frame
    double closest = 1e300;   // smallest separation over the checked frames [m]
    long crossedFrames = 0;
    SelfCollisionStats stats;
};

// Steps `solver` `steps` times, checking every `every` steps: crossings, and the closest pair
// of elements sharing no vertex (pairs beyond `cutoff` are not measured).
inline SelfCheck runAndCheck(Solver& solver, long steps, long every, double cutoff) {
    SelfCheck o;
    for (long done = 0; done < steps; done += every) {
        const StepResult r = solver.step(every);
        EXPECT_FALSE(r.unstable) << r.reason;
        if (r.unstable) break;
        const ref::TriangleMesh m = meshOf(solver.read());
        const long crossings = ref::countEdgeTriangleCrossings(m);
        o.worstCrossings = std::max(o.worstCrossings, crossings);
        o.crossedFrames += crossings > 0;
        o.closest = std::min(o.closest, ref::minimumSeparation(m, 0, cutoff).distance);
    }
    o.stats = solver.selfCollisionStats();
    return o;
}

}  // namespace cloth::test
