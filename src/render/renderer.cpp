#include "render/renderer.h"

#include <GL/glew.h>

#include <algorithm>
#include <cmath>

#include "model/stiffness.h"
#include "render/collider_draw.h"
#include "render/geometry.h"
#include "render/gl_program.h"

namespace cloth::render {
namespace {

// Colours (linear RGB). Front = the side the DESIGN.md §2 normal points to.
const glm::vec3 kFront0{0.86f, 0.36f, 0.16f}, kFront1{0.97f, 0.66f, 0.32f};
const glm::vec3 kBack0{0.16f, 0.34f, 0.72f}, kBack1{0.36f, 0.58f, 0.92f};
const glm::vec3 kWire{0.08f, 0.08f, 0.1f};
const glm::vec3 kPin{0.95f, 0.15f, 0.2f};
const glm::vec3 kContact{0.2f, 0.9f, 0.85f};
const glm::vec3 kWind{0.35f, 0.9f, 1.0f};
const glm::vec3 kFamilyColours[3] = {{1.0f, 0.3f, 0.25f}, {0.3f, 1.0f, 0.35f}, {1.0f, 0.4f, 1.0f}};
constexpr float kCheckers = 10;
constexpr GLuint kPositionBinding = 0;  // the SSBO binding the vertex shaders read (gpu_layout.h)

glm::vec3 lightDirection() {
    return glm::normalize(glm::vec3(0.35f, 1.0f, 0.45f));
}

// Two unit vectors spanning the plane with normal n.
void planeBasis(const glm::vec3& n, glm::vec3& t, glm::vec3& b) {
    const glm::vec3 other = std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    t = glm::normalize(glm::cross(other, n));
    b = glm::cross(n, t);
}

GLuint makeBuffer() {
    GLuint b = 0;
    glGenBuffers(1, &b);
    return b;
}

template <typename T>
void upload(GLenum target, GLuint buffer, const std::vector<T>& data) {
    glBindBuffer(target, buffer);
    glBufferData(target, GLsizeiptr(data.size() * sizeof(T)), data.data(), GL_DYNAMIC_DRAW);
}

}  // namespace

struct Renderer::Impl {
    GlProgram cloth{"render/cloth.vert", "render/cloth.frag"};
    GlProgram lines{"render/lines.vert", "render/lines.frag"};
    GlProgram springs{"render/springs.vert", "render/lines.frag"};
    GlProgram points{"render/points.vert", "render/points.frag"};

    GLuint clothVao = 0, clothIndices = 0, pinIndices = 0, contactIndices = 0, ownPositions = 0,
           ownNormals = 0;
    GLuint linesVao = 0, linesBuffer = 0;
    GLsizei clothIndexCount = 0, pinCount = 0, contactCount = 0;
    bool clothLines = false;
    GLuint positions = 0, normals = 0;  // the buffers drawn from now
    Scene scene;
    std::vector<glm::vec4> packedPositions, packedNormals;
    ColliderPainter colliders;
    double time = 0;                  // the solver's [s]
    std::vector<ColliderDrag> drags;  // the viewer's, by scene order

    Impl();
    ~Impl();
    void bindCloth() const;
    void drawCloth(const glm::mat4& viewProj, const RenderOptions& o) const;
    void drawMarkers(const glm::mat4& viewProj, const RenderOptions& o) const;
    void drawSprings(const glm::mat4& viewProj, const RenderOptions& o) const;
    void drawWind(const glm::mat4& viewProj) const;
    Bounds restBounds() const;
};

Renderer::Impl::Impl() {
    glGenVertexArrays(1, &clothVao);
    glGenVertexArrays(1, &linesVao);
    clothIndices = makeBuffer();
    pinIndices = makeBuffer();
    contactIndices = makeBuffer();
    ownPositions = makeBuffer();
    ownNormals = makeBuffer();
    linesBuffer = makeBuffer();
    // The cloth: vec4 positions and normals, 16-byte stride, from whichever buffers are current.
    glBindVertexArray(clothVao);
    for (GLuint a : {0u, 1u}) {
        glEnableVertexAttribArray(a);
        glVertexAttribFormat(a, 4, GL_FLOAT, GL_FALSE, 0);
        glVertexAttribBinding(a, a);
    }
    // Lines: interleaved position, colour.
    glBindVertexArray(linesVao);
    glBindBuffer(GL_ARRAY_BUFFER, linesBuffer);
    for (GLuint a : {0u, 1u}) {
        glEnableVertexAttribArray(a);
        glVertexAttribPointer(a, 3, GL_FLOAT, GL_FALSE, 2 * sizeof(glm::vec3),
                              reinterpret_cast<const void*>(std::uintptr_t(a * sizeof(glm::vec3))));
    }
    glBindVertexArray(0);
}

Renderer::Impl::~Impl() {
    const GLuint arrays[] = {clothVao, linesVao};
    glDeleteVertexArrays(2, arrays);
    const GLuint buffers[] = {clothIndices, pinIndices, contactIndices,
                              ownPositions, ownNormals, linesBuffer};
    glDeleteBuffers(5, buffers);
}

Renderer::Renderer() : impl_(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

void Renderer::setScene(const Scene& scene) {
    Impl& m = *impl_;
    const bool gridChanged = scene.cloth.nu != m.scene.cloth.nu ||
                             scene.cloth.nv != m.scene.cloth.nv || m.clothIndexCount == 0;
    m.scene = scene;
    m.colliders.setColliders(scene.colliders);
    if (!gridChanged) return;
    const ClothIndices c = clothIndices(scene.cloth.nu, scene.cloth.nv);
    glBindVertexArray(m.clothVao);
    upload(GL_ELEMENT_ARRAY_BUFFER, m.clothIndices, c.indices);
    glBindVertexArray(0);
    m.clothIndexCount = GLsizei(c.indices.size());
    m.clothLines = c.lines;
    haveCloth_ = false;
}

void Renderer::setPins(const std::vector<std::int64_t>& vertices) {
    std::vector<std::uint32_t> indices(vertices.begin(), vertices.end());
    upload(GL_ARRAY_BUFFER, impl_->pinIndices, indices);
    impl_->pinCount = GLsizei(indices.size());
}

void Renderer::setContacts(const std::vector<std::int64_t>& vertices) {
    std::vector<std::uint32_t> indices(vertices.begin(), vertices.end());
    upload(GL_ARRAY_BUFFER, impl_->contactIndices, indices);
    impl_->contactCount = GLsizei(indices.size());
}

void Renderer::setColliderDrags(const std::vector<ColliderDrag>& drags) {
    impl_->drags = drags;
    impl_->colliders.setPose(impl_->time, drags);
}

bool Renderer::updateCloth(const Solver& solver) {
    Impl& m = *impl_;
    m.time = solver.time();  // the colliders are drawn where the solver has them now
    m.colliders.setPose(m.time, m.drags);
    if (const std::optional<DrawBuffers> own = solver.drawBuffers()) {
        m.positions = own->positions;
        m.normals = own->normals;
        haveCloth_ = true;
        return true;
    }
    haveCloth_ = packCloth(solver.read(), m.packedPositions, m.packedNormals);
    if (!haveCloth_) return false;
    upload(GL_ARRAY_BUFFER, m.ownPositions, m.packedPositions);
    upload(GL_ARRAY_BUFFER, m.ownNormals, m.packedNormals);
    m.positions = m.ownPositions;
    m.normals = m.ownNormals;
    return true;
}

void Renderer::draw(const Camera& camera, const RenderOptions& o, int width, int height, int x) {
    const Impl& m = *impl_;
    glClearColor(o.background.x, o.background.y, o.background.z, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glViewport(x, 0, width, height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);  // markers drawn at a vertex already drawn (a chain's) still show
    glDisable(GL_CULL_FACE);
    glEnable(GL_PROGRAM_POINT_SIZE);
    const glm::mat4 viewProj =
        camera.projection(float(width) / float(std::max(height, 1))) * camera.view();
    m.cloth.use();
    m.cloth.set("uEye", camera.eye());
    m.cloth.set("uLightDir", lightDirection());
    if (o.colliders)
        m.colliders.draw(
            {viewProj, camera.eye(), lightDirection(), m.restBounds(), o.highlightCollider});
    if (haveCloth_) {
        m.bindCloth();
        m.drawCloth(viewProj, o);
        m.drawMarkers(viewProj, o);
        m.drawSprings(viewProj, o);
    }
    if (o.wind) m.drawWind(viewProj);
    glBindVertexArray(0);
    glUseProgram(0);
}

void Renderer::Impl::bindCloth() const {
    glBindVertexArray(clothVao);
    glBindVertexBuffer(0, positions, 0, sizeof(glm::vec4));
    glBindVertexBuffer(1, normals, 0, sizeof(glm::vec4));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPositionBinding, positions);
}

void Renderer::Impl::drawCloth(const glm::mat4& viewProj, const RenderOptions& o) const {
    const Grid g = scene.grid();
    cloth.use();
    cloth.set("uViewProj", viewProj);
    cloth.set("uGrid", glm::ivec2(g.nu, g.nv));
    cloth.set("uRest", glm::vec2(float(g.restLength(1, 0)), float(g.restLength(0, 1))));
    cloth.set("uColourMode", o.colour == ColourMode::Strain ? 1 : 0);
    cloth.set("uStrainScale", o.strainScale);
    cloth.set("uCheckers", kCheckers);
    cloth.set("uFront0", kFront0);
    cloth.set("uFront1", kFront1);
    cloth.set("uBack0", kBack0);
    cloth.set("uBack1", kBack1);
    if (clothLines) {
        cloth.set("uFlat", 1);
        cloth.set("uFlatColour", kFront1);
        glDrawElements(GL_LINE_STRIP, clothIndexCount, GL_UNSIGNED_INT, nullptr);
        return;
    }
    cloth.set("uFlat", 0);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1, 1);  // the wireframe pass draws on top
    glDrawElements(GL_TRIANGLES, clothIndexCount, GL_UNSIGNED_INT, nullptr);
    glDisable(GL_POLYGON_OFFSET_FILL);
    if (!o.wireframe) return;
    cloth.set("uFlat", 1);
    cloth.set("uFlatColour", kWire);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glDrawElements(GL_TRIANGLES, clothIndexCount, GL_UNSIGNED_INT, nullptr);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
}

void Renderer::Impl::drawMarkers(const glm::mat4& viewProj, const RenderOptions& o) const {
    points.use();
    points.set("uViewProj", viewProj);
    if (clothLines) {  // a chain: every vertex is a mass worth seeing
        points.set("uPointSize", 9.0f);
        points.set("uColour", kFront0);
        glDrawElements(GL_POINTS, clothIndexCount, GL_UNSIGNED_INT, nullptr);
    }
    if (o.contacts && contactCount > 0) {
        points.set("uPointSize", 6.0f);
        points.set("uColour", kContact);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, contactIndices);
        glDrawElements(GL_POINTS, contactCount, GL_UNSIGNED_INT, nullptr);
    }
    if (o.pins && pinCount > 0) {
        points.set("uPointSize", 11.0f);
        points.set("uColour", kPin);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, pinIndices);
        glDrawElements(GL_POINTS, pinCount, GL_UNSIGNED_INT, nullptr);
    }
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, clothIndices);
}

void Renderer::Impl::drawSprings(const glm::mat4& viewProj, const RenderOptions& o) const {
    const Grid g = scene.grid();
    springs.use();
    springs.set("uViewProj", viewProj);
    springs.set("uGrid", glm::ivec2(g.nu, g.nv));
    if (o.grabVertex && *o.grabVertex < g.count()) {
        springs.set("uMode", 1);
        springs.set("uCentre", int(*o.grabVertex));
        springs.set("uTarget", o.grabTarget);
        glDrawArrays(GL_LINES, 0, 2);
    }
    if (!o.springs) return;
    GLint offsets[12 * 3];
    for (std::size_t s = 0; s < kSpringOffsets.size(); ++s) {
        offsets[3 * s] = kSpringOffsets[s].di;
        offsets[3 * s + 1] = kSpringOffsets[s].dj;
        offsets[3 * s + 2] = GLint(kSpringOffsets[s].family);
    }
    glUniform3iv(glGetUniformLocation(springs.id(), "uOffsets"), 12, offsets);
    const GLint on[3] = {familyModelled(scene, Family::Structural),
                         familyModelled(scene, Family::Shear), familyModelled(scene, Family::Bend)};
    glUniform3iv(glGetUniformLocation(springs.id(), "uFamilyOn"), 1, on);
    glUniform3fv(glGetUniformLocation(springs.id(), "uFamilyColour"), 3, &kFamilyColours[0].x);
    springs.set("uMode", 0);
    std::vector<std::int64_t> vertices = o.springVertices;
    if (vertices.empty())
        vertices = {g.index(0, 0), g.index(g.nu / 2, 0), g.index(g.nu / 2, g.nv / 2)};
    glDisable(GL_DEPTH_TEST);  // an overlay: visible through the cloth
    for (const std::int64_t k : vertices) {
        if (k < 0 || k >= g.count()) continue;
        springs.set("uCentre", int(k));
        glDrawArrays(GL_LINES, 0, 24);
    }
    glEnable(GL_DEPTH_TEST);
}

void Renderer::Impl::drawWind(const glm::mat4& viewProj) const {
    if (!scene.wind || scene.wind->strength == 0) return;
    const Bounds rest = restBounds();
    const glm::vec3 dir = glm::normalize(glm::vec3(scene.wind->direction));
    // Above the cloth's rest centre, inside the framed view.
    const float length = 0.6f * std::max(rest.radius(), 0.3f);
    const glm::vec3 tail =
        rest.centre() + glm::vec3(0, 0.8f * rest.radius(), 0) - 0.5f * length * dir;
    const glm::vec3 head = tail + length * dir;
    glm::vec3 side, unused;
    planeBasis(dir, side, unused);
    const glm::vec3 back = head - 0.25f * length * dir;
    const std::vector<glm::vec3> v = {tail,
                                      kWind,
                                      head,
                                      kWind,
                                      head,
                                      kWind,
                                      back + 0.12f * length * side,
                                      kWind,
                                      head,
                                      kWind,
                                      back - 0.12f * length * side,
                                      kWind};
    glBindVertexArray(linesVao);
    upload(GL_ARRAY_BUFFER, linesBuffer, v);
    lines.use();
    lines.set("uViewProj", viewProj);
    glDrawArrays(GL_LINES, 0, GLsizei(v.size() / 2));
}

Bounds Renderer::Impl::restBounds() const {
    Bounds b;
    const Grid g = scene.grid();
    for (int j : {0, g.nv - 1})
        for (int i : {0, g.nu - 1}) b.add(glm::vec3(g.restPosition(i, j)));
    return b;
}

Bounds Renderer::sceneBounds() const {
    Bounds b = impl_->restBounds();
    b.add(impl_->colliders.bounds(b));
    return b;
}

Bounds stateBounds(const SimState& state) {
    Bounds b;
    for (const glm::dvec3& p : state.positions)
        if (std::isfinite(p.x + p.y + p.z)) b.add(glm::vec3(p));
    return b;
}

Camera framedCamera(const Renderer& renderer, float aspect, const SimState* state) {
    Bounds b = renderer.sceneBounds();
    if (state != nullptr) b.add(stateBounds(*state));
    Camera c;
    c.frame(b, aspect);
    return c;
}

}  // namespace cloth::render
