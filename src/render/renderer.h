// Draws a scene: the cloth straight from the solver's vec4 buffers (the GPU backend's SSBOs, or
// a buffer the CPU backend's state is uploaded into once per frame), the colliders at the
// solver's time (render/collider_draw.h), pins,
// optional wireframe, strain colours, a spring-family overlay and the wind arrow.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <vector>

#include "model/collider_pose.h"
#include "model/scene.h"
#include "render/camera.h"
#include "solver/solver.h"

namespace cloth::render {

enum class ColourMode { Checker, Strain };

struct RenderOptions {
    ColourMode colour = ColourMode::Checker;
    bool wireframe = false;
    bool pins = true;
    bool contacts = true;  // markers on the vertices in a self-contact (setContacts)
    bool colliders = true;
    bool wind = true;
    bool springs = false;                      // the overlay, for springVertices
    std::vector<std::int64_t> springVertices;  // empty: a default few (corner, edge, centre)
    float strainScale = 0.05f;                 // relative stretch shown at full colour
    std::optional<std::int64_t> grabVertex;    // draws the grab spring to grabTarget
    std::optional<int> highlightCollider;      // drawn lighter: the one being dragged
    glm::vec3 grabTarget{0};
    glm::vec3 background{0.11f, 0.12f, 0.15f};
};

class Renderer {
public:
    // Needs a current GL 4.3+ context with functions loaded (GlContext). Throws
    // std::runtime_error on a shader problem.
    Renderer();
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // The scene to draw: grid, colliders and wind. Cheap when only parameters changed.
    void setScene(const Scene& scene);
    // Vertex indices k = j·nu + i to mark as pinned.
    void setPins(const std::vector<std::int64_t>& vertices);
    // Vertex indices to mark as in a self-contact (Solver::selfContactVertices).
    void setContacts(const std::vector<std::int64_t>& vertices);
    // The viewer's collider drags (model/collider_pose.h), by the scene's collider order.
    void setColliderDrags(const std::vector<ColliderDrag>& drags);
    // Takes the solver's current state and time (colliders are drawn at their pose then): binds the
    // GPU solver's buffers (no copy), or reads the CPU solver's state and uploads it. Returns false
    // if the state is not finite: the cloth is then not drawn until a finite state arrives.
    bool updateCloth(const Solver& solver);
    // Forgets the cloth (e.g. after an instability); nothing is drawn for it.
    void clearCloth() { haveCloth_ = false; }

    // Clears the bound framebuffer and draws into its (x, 0, width, height) viewport.
    void draw(const Camera& camera, const RenderOptions& options, int width, int height, int x = 0);

    // The cloth's rest shape and the colliders where they are now, for framing the camera.
    Bounds sceneBounds() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    bool haveCloth_ = false;
};

// The bounding box of a state's finite positions.
Bounds stateBounds(const SimState& state);

// A camera that frames `renderer`'s scene (and `state`'s cloth, if given) from the default
// direction, in a view `aspect` = width / height.
Camera framedCamera(const Renderer& renderer, float aspect, const SimState* state = nullptr);

}  // namespace cloth::render
