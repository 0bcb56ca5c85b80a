// The 1x line of `clothsim bench speed`: the seed's explicit Euler written the straightforward
// way (one thread, double, each vertex visiting its 12 neighbours with bounds checks), sharing no
// code with the optimised solvers, and a CPU triad for the machine's memory bandwidth.
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <vector>

#include "model/scene.h"

namespace cloth::app {

// The scene's grid, springs, damping, gravity, mass, pins and dt; wind and colliders are not
// modelled (the speed benchmark's scene, hanging, has neither). A material runs as the seed's
// uniform cloth: an inner vertex's mass and drag everywhere, the structural springs along u and
// the shear springs at the material's constants, no bending: the seed's loop and work, the 1×.
class BaselineCloth {
public:
    explicit BaselineCloth(const Scene& scene);
    void step(long n);  // n explicit Euler steps (DESIGN.md §2, seed eq. (6))
    double x(std::size_t k) const { return x_[k].x; }
    // Position of vertex k = j·nu + i [m].
    glm::dvec3 position(std::size_t k) const { return {x_[k].x, x_[k].y, x_[k].z}; }

private:
    struct V3 {
        double x, y, z;
    };
    void stepOnce();

    Grid grid_;        // rest positions and rest lengths (model/grid.h)
    double rest_[12];  // rest length of each neighbour offset [m]
    int nu_, nv_;
    double dt_, mass_, damping_;
    double k_[3];  // structural, shear, bend [N/m]
    V3 gravity_;
    std::vector<V3> x_, v_, xNext_, vNext_;
    std::vector<char> pinned_;
};

// Best-of-`repeats` triad a[i] = b[i] + s·c[i] over three arrays of `bytesEach` on all hardware
// threads: (3·bytesEach)/best time [bytes/s] (two reads and a write; write-allocate not counted).
double measureTriadBandwidth(std::size_t bytesEach, int repeats);

}  // namespace cloth::app
