#include "render/collider_draw.h"

#include <GL/glew.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "model/collider_mesh.h"
#include "render/geometry.h"
#include "render/gl_program.h"

namespace cloth::render {
namespace {

const glm::vec3 kCollider{0.24f, 0.66f, 0.58f};   // teal
const glm::vec3 kHighlight{0.38f, 0.86f, 0.72f};  // the collider being dragged
constexpr float kThinner = 0.98f;                 // spheres and capsules, see the header

// Two unit vectors spanning the plane with normal n.
void planeBasis(const glm::vec3& n, glm::vec3& t, glm::vec3& b) {
    const glm::vec3 other = std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    t = glm::normalize(glm::cross(other, n));
    b = glm::cross(n, t);
}

// What the meshes depend on: the shapes' numbers (not thickness, friction or motion).
std::vector<double> shapeKey(const std::vector<Collider>& colliders) {
    std::vector<double> key;
    const auto put = [&](const glm::dvec3& v) { key.insert(key.end(), {v.x, v.y, v.z}); };
    for (const Collider& c : colliders) {
        key.push_back(double(c.shape.index()));
        if (const Sphere* s = c.as<Sphere>()) {
            put(s->center);
            key.push_back(s->radius);
        } else if (const Box* b = c.as<Box>()) {
            put(b->center);
            put(b->halfExtents);
            put(b->rotation.axis);
            key.push_back(b->rotation.degrees);
        } else if (const Capsule* cap = c.as<Capsule>()) {
            put(cap->a);
            put(cap->b);
            key.push_back(cap->radius);
        } else if (const MeshCollider* m = c.as<MeshCollider>()) {
            key.push_back(double(reinterpret_cast<std::uintptr_t>(m->baked.get())));
            put(m->translation);
            put(m->rotation.axis);
            key.push_back(m->rotation.degrees);
        }
    }
    return key;
}

glm::mat4 modelMatrix(const Pose& q) {
    glm::mat4 m(glm::mat3(q.rotation));
    m[3] = glm::vec4(glm::vec3(q.translation), 1);
    return m;
}

}  // namespace

struct ColliderPainter::Impl {
    GlProgram mesh{"render/mesh.vert", "render/mesh.frag"};
    GlProgram ground{"render/ground.vert", "render/ground.frag"};
    GLuint emptyVao = 0;
    struct Piece {
        std::size_t index = 0;  // in colliders
        GLuint vao = 0, buffer = 0;
        GLsizei count = 0;
        Bounds rest;  // of the mesh at t = 0
    };
    std::vector<Piece> pieces;
    std::vector<Collider> colliders;
    std::vector<double> key;
    bool built = false;
    double time = 0;
    std::vector<ColliderDrag> drags;

    Impl() { glGenVertexArrays(1, &emptyVao); }
    ~Impl() {
        clear();
        glDeleteVertexArrays(1, &emptyVao);
    }
    void clear() {
        for (const Piece& p : pieces) {
            glDeleteVertexArrays(1, &p.vao);
            glDeleteBuffers(1, &p.buffer);
        }
        pieces.clear();
    }
    Pose poseOf(std::size_t k) const {
        return colliderPose(colliders[k], time, k < drags.size() ? &drags[k] : nullptr);
    }
    void build();
    void drawGround(const Frame& f) const;
    void drawMeshes(const Frame& f) const;
};

void ColliderPainter::Impl::build() {
    clear();
    std::vector<Collider> drawn = colliders;
    for (Collider& c : drawn) {
        if (Sphere* s = c.as<Sphere>()) s->radius *= kThinner;
        if (Capsule* cap = c.as<Capsule>()) cap->radius *= kThinner;
    }
    const auto meshes = colliderMeshes(drawn, 1.0);
    for (std::size_t k = 0; k < drawn.size(); ++k) {
        if (drawn[k].as<Plane>() != nullptr) continue;  // the ground grid
        const LitMesh lit = litMesh(meshes[k].second);
        std::vector<glm::vec3> interleaved;  // position, normal
        Piece p;
        p.index = k;
        for (std::size_t v = 0; v < lit.positions.size(); ++v) {
            interleaved.insert(interleaved.end(), {lit.positions[v], lit.normals[v]});
            p.rest.add(lit.positions[v]);
        }
        p.count = GLsizei(lit.positions.size());
        glGenVertexArrays(1, &p.vao);
        glGenBuffers(1, &p.buffer);
        glBindVertexArray(p.vao);
        glBindBuffer(GL_ARRAY_BUFFER, p.buffer);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(interleaved.size() * sizeof(glm::vec3)),
                     interleaved.data(), GL_STATIC_DRAW);
        for (GLuint a : {0u, 1u}) {
            glEnableVertexAttribArray(a);
            glVertexAttribPointer(
                a, 3, GL_FLOAT, GL_FALSE, 2 * sizeof(glm::vec3),
                reinterpret_cast<const void*>(std::uintptr_t(a * sizeof(glm::vec3))));
        }
        pieces.push_back(p);
    }
    glBindVertexArray(0);
}

ColliderPainter::ColliderPainter() : impl_(std::make_unique<Impl>()) {}
ColliderPainter::~ColliderPainter() = default;

void ColliderPainter::setColliders(const std::vector<Collider>& colliders) {
    Impl& m = *impl_;
    m.colliders = colliders;
    std::vector<double> key = shapeKey(colliders);
    if (m.built && key == m.key) return;
    m.key = std::move(key);
    m.build();
    m.built = true;
}

void ColliderPainter::setPose(double time, const std::vector<ColliderDrag>& drags) {
    impl_->time = time;
    impl_->drags = drags;
}

void ColliderPainter::draw(const Frame& f) const {
    for (const GlProgram* p : {&impl_->mesh, &impl_->ground}) {
        p->use();
        p->set("uEye", f.eye);
        p->set("uLightDir", f.lightDir);
    }
    impl_->drawGround(f);
    impl_->drawMeshes(f);
}

void ColliderPainter::Impl::drawGround(const Frame& f) const {
    const float halfSize = std::max(3.0f * f.cloth.radius(), 2.0f);
    glBindVertexArray(emptyVao);
    ground.use();
    ground.set("uViewProj", f.viewProj);
    ground.set("uHalfSize", halfSize);
    ground.set("uSpacing", halfSize > 20 ? 1.0f : 0.1f);
    for (std::size_t k = 0; k < colliders.size(); ++k) {
        const Plane* p = colliders[k].as<Plane>();
        if (p == nullptr) continue;
        const Pose q = poseOf(k);
        const glm::vec3 n(q.rotation * p->normal), point(q.apply(p->point));
        glm::vec3 t, b;
        planeBasis(n, t, b);
        // Centred under the cloth: its rest centre projected onto the plane.
        const glm::vec3 centre = f.cloth.centre() - glm::dot(f.cloth.centre() - point, n) * n;
        ground.set("uCentre", centre);
        ground.set("uTangent", t);
        ground.set("uBitangent", b);
        ground.set("uNormal", n);
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    }
}

void ColliderPainter::Impl::drawMeshes(const Frame& f) const {
    mesh.use();
    mesh.set("uViewProj", f.viewProj);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(2, 2);  // behind a cloth lying on a face (the cloth's own offset is 1, 1)
    for (const Piece& p : pieces) {
        const bool lit = f.highlight && std::size_t(*f.highlight) == p.index;
        mesh.set("uColour", lit ? kHighlight : kCollider);
        mesh.set("uModel", modelMatrix(poseOf(p.index)));
        glBindVertexArray(p.vao);
        glDrawArrays(GL_TRIANGLES, 0, p.count);
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
}

Bounds ColliderPainter::bounds(const Bounds& cloth) const {
    const Impl& m = *impl_;
    Bounds b;
    for (std::size_t k = 0; k < m.colliders.size(); ++k) {
        const Plane* p = m.colliders[k].as<Plane>();
        if (p == nullptr) continue;  // its point under the cloth: the cloth may fall to it
        const Pose q = m.poseOf(k);
        const glm::vec3 n(q.rotation * p->normal), centre = cloth.centre();
        b.add(centre - glm::dot(centre - glm::vec3(q.apply(p->point)), n) * n);
    }
    for (const Impl::Piece& piece : m.pieces) {
        const glm::mat4 model = modelMatrix(m.poseOf(piece.index));
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 r((corner & 1) ? piece.rest.hi.x : piece.rest.lo.x,
                              (corner & 2) ? piece.rest.hi.y : piece.rest.lo.y,
                              (corner & 4) ? piece.rest.hi.z : piece.rest.lo.z);
            b.add(glm::vec3(model * glm::vec4(r, 1)));
        }
    }
    return b;
}

}  // namespace cloth::render
