// C++ mirrors of the std430 blocks in shaders/compute/layout.glsl (DESIGN.md §3). Every member
// is a 16-byte vec4/ivec4 so std430 and C++ agree; the static_asserts keep them agreeing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>

namespace cloth::gpu {

// Binding points of the shader storage blocks, as in layout.glsl.
enum Binding : unsigned {
    kPositions = 0,   // vec4 per vertex: xyz [m], w inverse mass [1/kg], 0 for a pinned vertex
    kVelocities = 1,  // vec4 per vertex: xyz [m/s], w the pinned vertex's slot in kPins
    kForces = 2,      // vec4 per vertex: spring + wind force [N]
    kNormals = 3,     // vec4 per vertex: unit normal (0 where undefined)
    kParams = 4,      // one Params
    kColliders = 5,   // planes (point, normal) then spheres (centre, radius), see layout.glsl
    kPins = 6,        // vec4 per pin: pinned position [m]
    kStatus = 7,      // one Status
    kBindingCount = 8
};

// Uniform locations. integrate.comp: the 1-based global step number. forces.comp: the grab
// (Solver::setGrab), int vertex (-1: none) and vec4 (target [m], stiffness [N/m]).
inline constexpr int kStepLocation = 0;
inline constexpr int kGrabVertexLocation = 0, kGrabLocation = 1;

struct Params {
    glm::ivec4 grid;          // nu, nv, 0, 0
    glm::vec4 stiffness;      // K structural, shear, bend [N/m], 0
    glm::vec4 restLength[3];  // L of kSpringOffsets[o] at [o / 4][o % 4] [m]
    glm::vec4 gravity;        // xyz g [m/s²], w damping μ [N·s/m]
    glm::vec4 wind;           // xyz unit direction, w strength K_w [N]
    glm::vec4 integration;    // x Δt [s], y max_speed² [m²/s²], zw 0
};
static_assert(sizeof(Params) == 128);
static_assert(offsetof(Params, grid) == 0);
static_assert(offsetof(Params, stiffness) == 16);
static_assert(offsetof(Params, restLength) == 32);
static_assert(offsetof(Params, gravity) == 80);
static_assert(offsetof(Params, wind) == 96);
static_assert(offsetof(Params, integration) == 112);

// Written by integrate.comp when a vertex goes bad (DESIGN.md §2 "Instability").
struct Status {
    std::uint32_t firstBadStep;  // 1-based global step, atomicMin; kNoBadStep while stable
    std::uint32_t badVertex;     // k of one vertex that went bad at that step
    std::uint32_t badKind;       // kBadNonFinite or kBadSpeed
    float badSpeed;              // |v| there [m/s]
};
static_assert(sizeof(Status) == 16);
static_assert(offsetof(Status, firstBadStep) == 0);
static_assert(offsetof(Status, badVertex) == 4);
static_assert(offsetof(Status, badKind) == 8);
static_assert(offsetof(Status, badSpeed) == 12);
inline constexpr std::uint32_t kNoBadStep = 0xffffffffu;
inline constexpr std::uint32_t kBadNonFinite = 1, kBadSpeed = 2;

static_assert(sizeof(glm::vec4) == 16 && sizeof(glm::ivec4) == 16);

}  // namespace cloth::gpu
