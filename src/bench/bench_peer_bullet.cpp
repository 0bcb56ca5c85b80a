// Bullet's btSoftBody as bench speed's peer (built only with libbullet-dev: CLOTH_HAVE_BULLET).
// The scene's nu × nv grid becomes a patch of nodes with the same 12-neighbour links, pinned
// corners of mass 0, in a btSoftRigidDynamicsWorld stepped once per dt with Bullet's default
// solver settings. Bullet's model differs from ours (docs/performance.md, "Peer: Bullet
// btSoftBody"): links are position constraints relaxed by iterations, not forces.
#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cstdio>
#include <memory>

#include "bench/bench_peer.h"

namespace cloth::app {
namespace {

btVector3 bt(const glm::dvec3& v) {
    return btVector3(btScalar(v.x), btScalar(v.y), btScalar(v.z));
}

class BulletCloth final : public PeerCloth {
public:
    explicit BulletCloth(const Scene& scene);
    ~BulletCloth() override;
    void step(long n) override;
    std::vector<glm::dvec3> positions() const override;
    std::string describe() const override { return description_; }
    std::string method() const override;
    double bytesPerVertex() const override;

private:
    void addLinks(const Scene& scene);

    double dt_;
    int nu_, nv_;
    btSoftBodyRigidBodyCollisionConfiguration collision_;
    btCollisionDispatcher dispatcher_{&collision_};
    btDbvtBroadphase broadphase_;
    btSequentialImpulseConstraintSolver solver_;
    std::unique_ptr<btSoftRigidDynamicsWorld> world_;
    btSoftBody* body_ = nullptr;  // owned: removed from the world and deleted in ~BulletCloth
    std::string description_;
};

BulletCloth::BulletCloth(const Scene& scene)
    : dt_(scene.integrator.dt), nu_(scene.cloth.nu), nv_(scene.cloth.nv) {
    world_ = std::make_unique<btSoftRigidDynamicsWorld>(&dispatcher_, &broadphase_, &solver_,
                                                        &collision_);
    world_->setGravity(bt(scene.gravity));
    btSoftBodyWorldInfo& info = world_->getWorldInfo();
    info.m_gravity = bt(scene.gravity);  // the soft body reads gravity here, not from the world
    info.m_sparsesdf.Initialize();

    const Grid grid = scene.grid();
    const auto& c = scene.cloth;
    std::vector<btVector3> x(std::size_t(grid.count()));
    std::vector<btScalar> m(x.size(), btScalar(c.mass));
    for (int j = 0; j < nv_; ++j)
        for (int i = 0; i < nu_; ++i)
            x[std::size_t(grid.index(i, j))] = bt(grid.restPosition(i, j));
    for (const Pin& p : scene.pins) m[std::size_t(p.j) * nu_ + p.i] = 0;  // mass 0: fixed
    body_ = new btSoftBody(&info, int(x.size()), x.data(), m.data());
    addLinks(scene);
    body_->m_cfg.kDP = btScalar(bulletDamping(scene.damping, c.mass, dt_));
    body_->updateConstants();  // rest lengths and the links' (1/m_a + 1/m_b)/kLST
    body_->setActivationState(DISABLE_DEACTIVATION);  // or it falls asleep and looks fast
    world_->addSoftBody(body_);

    const auto& cfg = body_->m_cfg;
    char text[512];
    std::snprintf(text, sizeof text,
                  "Bullet %s btSoftBody (%s precision, one thread): %d position, %d velocity, "
                  "%d drift iterations; kLST structural %.3g shear %.3g bend %.3g (from K, m, dt); "
                  "kDP %.3g (from damping); collisions 0x%x",
                  CLOTH_BULLET_VERSION, sizeof(btScalar) == 8 ? "double" : "single",
                  cfg.piterations, cfg.viterations, cfg.diterations,
                  bulletLinkStiffness(scene.springs.structural, c.mass, dt_),
                  bulletLinkStiffness(scene.springs.shear, c.mass, dt_),
                  bulletLinkStiffness(scene.springs.bend, c.mass, dt_), double(cfg.kDP),
                  unsigned(cfg.collisions));
    description_ = text;
}

// The 12-neighbour stencil of DESIGN.md §2 as links, each pair once (the offsets pointing
// forward in k), one material per family with its mapped kLST; a family of stiffness 0 gets none.
void BulletCloth::addLinks(const Scene& scene) {
    btSoftBody::Material* materials[kFamilyCount] = {};
    for (int f = 0; f < kFamilyCount; ++f) {
        const double k = scene.springs.of(Family(f));
        if (k <= 0) continue;
        materials[f] = body_->appendMaterial();
        materials[f]->m_kLST = btScalar(bulletLinkStiffness(k, scene.cloth.mass, dt_));
    }
    for (const SpringOffset& o : kSpringOffsets) {
        btSoftBody::Material* material = materials[int(o.family)];
        if (material == nullptr || o.dj < 0 || (o.dj == 0 && o.di < 0)) continue;
        for (int j = 0; j < nv_; ++j)
            for (int i = 0; i < nu_; ++i)
                if (i + o.di >= 0 && i + o.di < nu_ && j + o.dj < nv_)
                    body_->appendLink(j * nu_ + i, (j + o.dj) * nu_ + i + o.di, material);
    }
}

BulletCloth::~BulletCloth() {
    world_->removeSoftBody(body_);
    delete body_;
}

void BulletCloth::step(long n) {
    // maxSubSteps 0: one internal step of exactly dt, no interpolation.
    for (long s = 0; s < n; ++s) world_->stepSimulation(btScalar(dt_), 0);
}

std::vector<glm::dvec3> BulletCloth::positions() const {
    std::vector<glm::dvec3> p;
    p.reserve(std::size_t(body_->m_nodes.size()));
    for (int k = 0; k < body_->m_nodes.size(); ++k) {
        const btVector3& x = body_->m_nodes[k].m_x;
        p.emplace_back(x.x(), x.y(), x.z());
    }
    return p;
}

std::string BulletCloth::method() const {
    return "pbd_" + std::to_string(body_->m_cfg.piterations) + "_iteration" +
           (body_->m_cfg.piterations == 1 ? "" : "s");
}

// Nodes, links and the nodes' AABB tree (a leaf per node, one inner node per pair): the arrays
// a step walks; materials and the world's fixed overhead left out.
double BulletCloth::bytesPerVertex() const {
    const double nodes = body_->m_nodes.size(), leaves = body_->m_ndbvt.m_leaves;
    return (nodes * sizeof(btSoftBody::Node) + body_->m_links.size() * sizeof(btSoftBody::Link) +
            std::max(0.0, 2 * leaves - 1) * sizeof(btDbvtNode)) /
           nodes;
}

}  // namespace

std::unique_ptr<PeerCloth> makeBulletCloth(const Scene& scene) {
    return std::make_unique<BulletCloth>(scene);
}

}  // namespace cloth::app
