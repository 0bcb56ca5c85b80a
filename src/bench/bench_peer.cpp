// Which peers this build has: Bullet when CMake found libbullet-dev (CLOTH_HAVE_BULLET).
#include "bench/bench_peer.h"

#include <stdexcept>

namespace cloth::app {

#ifdef CLOTH_HAVE_BULLET
std::unique_ptr<PeerCloth> makeBulletCloth(const Scene& scene);  // bench_peer_bullet.cpp
#endif

std::optional<std::string> peerUnavailable(const std::string& name) {
    if (name != "bullet") return "unknown peer '" + name + "'; expected bullet";
#ifdef CLOTH_HAVE_BULLET
    return std::nullopt;
#else
    return "this clothsim was built without Bullet (libbullet-dev was not found when CMake ran, "
           "or -DCLOTH_BULLET=OFF): apt-get install libbullet-dev, then configure and build again";
#endif
}

std::unique_ptr<PeerCloth> makePeerCloth(const std::string& name, const Scene& scene) {
    if (const auto why = peerUnavailable(name)) throw std::logic_error(*why);
#ifdef CLOTH_HAVE_BULLET
    return makeBulletCloth(scene);
#else
    (void)scene;
    return nullptr;
#endif
}

}  // namespace cloth::app
