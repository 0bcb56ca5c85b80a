#include "reference/reference_colliders.h"

#include <algorithm>
#include <cmath>

#include "reference/vector_ops.h"

namespace ref {

V3 rotate(const V3& axis, double degrees, const V3& v) {
    const double pi = std::acos(-1.0);
    const double t = degrees * pi / 180;
    const V3 k = normalised(axis);
    return add(add(scale(std::cos(t), v), scale(std::sin(t), cross(k, v))),
               scale(dot(k, v) * (1 - std::cos(t)), k));
}

Contact planeContact(const Plane& plane, const V3& p) {
    const V3 n = normalised(plane.normal);
    return {dot(sub(p, plane.point), n), n};
}

Contact sphereContact(const Sphere& sphere, const V3& p) {
    const V3 r = sub(p, sphere.center);
    const double d = norm(r);
    return {d - sphere.radius, d > 0 ? scale(1 / d, r) : V3{0, 1, 0}};
}

Contact boxContact(const Box& box, const V3& p) {
    // The box's axes are the rotated x, y, z; q are p's coordinates along them.
    V3 axes[3];
    double q[3];
    for (int i = 0; i < 3; ++i) {
        V3 e{0, 0, 0};
        e[i] = 1;
        axes[i] = rotate(box.axis, box.degrees, e);
        q[i] = dot(sub(p, box.center), axes[i]);
    }
    // Outside: the clamped point is the closest point of the box.
    double away[3];
    bool outside = false;
    for (int i = 0; i < 3; ++i) {
        const double c = std::max(-box.half[i], std::min(box.half[i], q[i]));
        away[i] = q[i] - c;
        if (away[i] != 0) outside = true;
    }
    if (outside) {
        const double d = std::sqrt(away[0] * away[0] + away[1] * away[1] + away[2] * away[2]);
        V3 n{0, 0, 0};
        for (int i = 0; i < 3; ++i) n = add(n, scale(away[i] / d, axes[i]));
        return {d, n};
    }
    // Inside: the nearest of the six faces.
    double best = INFINITY;
    V3 n{0, 0, 0};
    for (int i = 0; i < 3; ++i) {
        for (const double side : {1.0, -1.0}) {
            const double gap = box.half[i] - side * q[i];  // distance to the face side·half
            if (gap < best) {
                best = gap;
                n = scale(side, axes[i]);
            }
        }
    }
    return {-best, n};
}

Contact capsuleContact(const Capsule& c, const V3& p) {
    const V3 ab = sub(c.b, c.a);
    double t = dot(sub(p, c.a), ab) / dot(ab, ab);
    t = std::max(0.0, std::min(1.0, t));
    const V3 r = sub(p, add(c.a, scale(t, ab)));
    const double d = norm(r);
    return {d - c.radius, scale(1 / d, r)};
}

Contact gridContact(const Grid& g, const V3& p) {
    int i0[3];
    double f[3];
    for (int a = 0; a < 3; ++a) {
        const double u = (p[a] - g.origin[a]) / g.cell;
        i0[a] = std::min(int(std::floor(u)), g.count[a] - 2);
        f[a] = u - i0[a];
    }
    double phi = 0;
    V3 grad{0, 0, 0};
    for (int dz = 0; dz < 2; ++dz)
        for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx) {
                const int d[3] = {dx, dy, dz};
                const double value =
                    g.values[(size_t(i0[2] + dz) * g.count[1] + (i0[1] + dy)) * g.count[0] +
                             (i0[0] + dx)];
                double w[3], dw[3];  // weight per axis and its derivative along that axis
                for (int a = 0; a < 3; ++a) {
                    w[a] = d[a] ? f[a] : 1 - f[a];
                    dw[a] = d[a] ? 1 : -1;
                }
                phi += w[0] * w[1] * w[2] * value;
                grad[0] += dw[0] * w[1] * w[2] * value;
                grad[1] += w[0] * dw[1] * w[2] * value;
                grad[2] += w[0] * w[1] * dw[2] * value;
            }
    return {phi, normalised(grad)};
}

namespace {
double segmentDistance(const V3& p, const V3& a, const V3& b) {
    const V3 ab = sub(b, a);
    const double t = std::max(0.0, std::min(1.0, dot(sub(p, a), ab) / dot(ab, ab)));
    return norm(sub(p, add(a, scale(t, ab))));
}
}  // namespace

double triangleDistance(const V3& p, const V3& a, const V3& b, const V3& c) {
    const V3 n = normalised(cross(sub(b, a), sub(c, a)));
    const double h = dot(sub(p, a), n);
    const V3 foot = sub(p, scale(h, n));
    // The foot is inside when it is on the inner side of all three edges.
    const V3* v[3] = {&a, &b, &c};
    bool inside = true;
    for (int e = 0; e < 3; ++e) {
        const V3& s = *v[e];
        const V3& t = *v[(e + 1) % 3];
        if (dot(cross(sub(t, s), sub(foot, s)), n) < 0) inside = false;
    }
    if (inside) return std::abs(h);
    return std::min({segmentDistance(p, a, b), segmentDistance(p, b, c), segmentDistance(p, c, a)});
}

bool respond(const Contact& c, double thickness, double friction, const V3& vc, V3& p, V3& v) {
    if (!(c.phi < thickness)) return false;
    p = add(p, scale(thickness - c.phi, c.normal));
    const V3 w = sub(v, vc);
    const double wn = dot(w, c.normal);
    const V3 wt = sub(w, scale(wn, c.normal));
    const double slide = norm(wt);
    const double keep = slide > 0 ? std::max(0.0, 1 - friction * std::abs(wn) / slide) : 0.0;
    v = add(vc, scale(keep, wt));
    return true;
}

namespace {

// The motion's turn [degrees] and shift [m] at time t: x(t) = pivot + rot(x₀ − pivot) + shift.
void motionAt(const Motion& m, double t, double& degrees, V3& shift) {
    const double pi = std::acos(-1.0);
    degrees = 0;
    shift = {0, 0, 0};
    switch (m.type) {
        case Motion::Type::None:
            break;
        case Motion::Type::Linear:
            shift = scale(t, m.velocity);
            break;
        case Motion::Type::Rotation:
            degrees = m.degreesPerSecond * t;
            break;
        case Motion::Type::Oscillation:
            shift =
                scale(m.amplitude * std::sin(2 * pi * m.frequency * t + m.phaseDegrees * pi / 180),
                      normalised(m.axis));
            break;
    }
}

// The grid posed by a rotation about its origin and a translation; outside the grid the
// clamped point's value plus the distance to it.
Contact posedGridContact(const Collider& c, const V3& p) {
    const V3 local = rotate(c.gridAxis, -c.gridDegrees, sub(p, c.gridTranslation));
    const Grid& g = c.grid;
    V3 q = local;
    for (int a = 0; a < 3; ++a) {
        const double lo = g.origin[a], hi = g.origin[a] + (g.count[a] - 1) * g.cell;
        q[a] = std::min(std::max(local[a], lo), hi);
    }
    Contact k = gridContact(g, q);
    k.phi += norm(sub(local, q));
    k.normal = rotate(c.gridAxis, c.gridDegrees, k.normal);
    return k;
}

Contact restContact(const Collider& c, const V3& p) {
    switch (c.shape) {
        case Collider::Shape::Plane:
            return planeContact(c.plane, p);
        case Collider::Shape::Sphere:
            return sphereContact(c.sphere, p);
        case Collider::Shape::Box:
            return boxContact(c.box, p);
        case Collider::Shape::Capsule:
            return capsuleContact(c.capsule, p);
        case Collider::Shape::Grid:
            return posedGridContact(c, p);
    }
    return {1, {0, 1, 0}};
}

}  // namespace

// d/dt of the motion at the point p (which moves with the collider).
V3 motionVelocity(const Motion& m, double t, const V3& p) {
    const double pi = std::acos(-1.0);
    switch (m.type) {
        case Motion::Type::None:
            return {0, 0, 0};
        case Motion::Type::Linear:
            return m.velocity;
        case Motion::Type::Rotation:
            return cross(scale(m.degreesPerSecond * pi / 180, normalised(m.axis)), sub(p, m.pivot));
        case Motion::Type::Oscillation: {
            const double w = 2 * pi * m.frequency;
            return scale(w * m.amplitude * std::cos(w * t + m.phaseDegrees * pi / 180),
                         normalised(m.axis));
        }
    }
    return {0, 0, 0};
}

V3 motionPoint(const Motion& m, double t, const V3& x0) {
    double degrees;
    V3 shift;
    motionAt(m, t, degrees, shift);
    const V3 axis = m.type == Motion::Type::Rotation ? m.axis : V3{0, 1, 0};
    return add(add(m.pivot, rotate(axis, degrees, sub(x0, m.pivot))), shift);
}

void collideMoving(const Collider& c, double t, V3& p, V3& v) {
    double degrees;
    V3 shift;
    motionAt(c.motion, t, degrees, shift);
    const V3 axis = c.motion.type == Motion::Type::Rotation ? c.motion.axis : V3{0, 1, 0};
    const V3 pivot = c.motion.pivot;
    // Back to the collider's rest frame: undo the shift, then the turn about the pivot.
    const V3 rest = add(pivot, rotate(axis, -degrees, sub(sub(p, shift), pivot)));
    Contact k = restContact(c, rest);
    k.normal = rotate(axis, degrees, k.normal);
    respond(k, c.thickness, c.friction, motionVelocity(c.motion, t, p), p, v);
}

}  // namespace ref
