#include "solver/solver.h"

#include <limits>
#include <tuple>

#include "model/bending.h"
#include "model/stiffness.h"

namespace cloth {

const char* backendName(Backend b) {
    return b == Backend::Cpu ? "cpu" : "gpu";
}
const char* precisionName(Precision p) {
    return p == Precision::Float ? "float" : "double";
}

Features Features::of(const Scene& scene) {
    Features f;
    f.structural = familyModelled(scene, Family::Structural);
    f.shear = familyModelled(scene, Family::Shear);
    f.bend = familyModelled(scene, Family::Bend);
    f.wind = scene.wind.has_value() && scene.wind->strength != 0;
    f.bending = bendingWeights(scene.grid(), scene.bendingStiffness()).active();
    f.borderShares = scene.material.has_value() && f.structural;
    f.springDamping = scene.springDamping() > 0 && (f.structural || f.shear || f.bend);
    f.planes = scene.planeCount();
    f.spheres = scene.sphereCount();
    f.boxes = scene.count<Box>();
    f.capsules = scene.count<Capsule>();
    f.meshes = scene.count<MeshCollider>();
    for (const Collider& c : scene.colliders) f.contactExtras += !c.plain();
    f.selfCollision = scene.selfCollision.has_value();
    f.stepControl = scene.integrator.maxStepStrain > 0;
    return f;
}

std::string Features::describe() const {
    std::string springs;
    for (auto [on, name] : {std::pair{structural, "structural"}, {shear, "shear"}, {bend, "bend"}})
        if (on) {
            if (!springs.empty()) springs += '+';
            springs += name;
        }
    std::string s = springs.empty() ? "no springs" : springs;
    if (bending) s += ", bending";
    if (springDamping) s += ", spring damping";
    if (wind) s += ", wind";
    for (auto [n, one, many] : {std::tuple{planes, "plane", "planes"},
                                {spheres, "sphere", "spheres"},
                                {boxes, "box", "boxes"},
                                {capsules, "capsule", "capsules"},
                                {meshes, "mesh", "meshes"}})
        if (n) s += ", " + std::to_string(n) + " " + (n == 1 ? one : many);
    if (contactExtras)
        s += ", " + std::to_string(contactExtras) + " with thickness, friction or motion";
    if (selfCollision) s += ", self-collision";
    if (stepControl) s += ", step control";
    return s;
}

PassTimes Solver::timePasses(int) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan};
}

}  // namespace cloth
