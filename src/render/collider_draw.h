// Draws a scene's colliders at their pose at one time (the solver's): planes as the fading ground
// grid, every other shape as the triangle mesh model/collider_mesh.h builds for it, uploaded once
// per change of shape and placed each frame by its pose (model/collider_pose.h: the motion, then
// the viewer's drag). Spheres and capsules are drawn 2 % thinner: a cloth resting on one touches
// it at its vertices only, and its flat triangles would cut into a full-size surface; flat faces
// are pushed back in depth instead, so a cloth lying on them with no thickness stays in front.
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <vector>

#include "model/collider_pose.h"
#include "model/scene.h"
#include "render/camera.h"

namespace cloth::render {

class ColliderPainter {
public:
    ColliderPainter();  // needs a current GL context; throws std::runtime_error on a shader error
    ~ColliderPainter();
    ColliderPainter(const ColliderPainter&) = delete;
    ColliderPainter& operator=(const ColliderPainter&) = delete;

    // The colliders to draw (scene order); their meshes are rebuilt only when a shape changed.
    void setColliders(const std::vector<Collider>& colliders);
    // The time [s] to pose them at and the viewer's drags (by scene order; missing: none).
    void setPose(double time, const std::vector<ColliderDrag>& drags);

    struct Frame {
        glm::mat4 viewProj{1};
        glm::vec3 eye{0}, lightDir{0, 1, 0};
        Bounds cloth;  // the cloth's rest bounds: the ground grid is centred under it
        std::optional<int> highlight;  // a collider drawn lighter (the one being dragged)
    };
    void draw(const Frame& frame) const;
    // The posed shapes' bounds (planes: the point under `cloth`'s centre).
    Bounds bounds(const Bounds& cloth) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace cloth::render
