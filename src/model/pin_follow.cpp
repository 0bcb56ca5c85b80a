#include "model/pin_follow.h"

#include <string>

#include "model/errors.h"

namespace cloth {
namespace {

std::string followKey(std::size_t k) {
    return "pins[" + std::to_string(k) + "].follow";
}

}  // namespace

bool follows(const Scene& scene, const Pin& pin) {
    return pin.follow >= 0 && std::size_t(pin.follow) < scene.colliders.size() &&
           scene.colliders[std::size_t(pin.follow)].motion.has_value();
}

Scene keepColliders(const Scene& scene, const std::vector<bool>& keep) {
    Scene s = scene;
    s.colliders.clear();
    std::vector<int> index(scene.colliders.size(), -1);
    for (std::size_t c = 0; c < scene.colliders.size(); ++c) {
        if (c < keep.size() && !keep[c]) continue;
        index[c] = int(s.colliders.size());
        s.colliders.push_back(scene.colliders[c]);
    }
    for (Pin& p : s.pins)
        if (p.follow >= 0)
            p.follow = std::size_t(p.follow) < index.size() ? index[std::size_t(p.follow)] : -1;
    return s;
}

std::vector<FollowPin> followPins(const Scene& scene) {
    const Grid grid = scene.grid();
    std::vector<FollowPin> out;
    for (const Pin& p : scene.pins) {
        if (!follows(scene, p)) continue;
        out.push_back({grid.index(p.i, p.j), p.follow,
                       scene.colliders[std::size_t(p.follow)].motion->motion(),
                       grid.restPosition(p.i, p.j)});
    }
    return out;
}

void checkFollowPins(const Scene& scene) {
    const int count = int(scene.colliders.size());
    for (std::size_t k = 0; k < scene.pins.size(); ++k) {
        const int n = scene.pins[k].follow;
        if (n < 0) continue;
        if (n >= count)
            throw InputError(scene.source, followKey(k),
                             "collider " + std::to_string(n) + " does not exist (the scene has " +
                                 std::to_string(count) + " colliders, numbered from 0)");
        if (!scene.colliders[std::size_t(n)].motion)
            throw InputError(scene.source, followKey(k),
                             "colliders[" + std::to_string(n) +
                                 "] has no motion: a pin can only follow a moving collider "
                                 "(a still pin is [i, j])");
    }
}

}  // namespace cloth
