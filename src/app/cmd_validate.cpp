// clothsim validate SCENE: checks a scene and prints what it models (DESIGN.md §5).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/backend_flags.h"
#include "app/cli.h"
#include "app/reports.h"
#include "backends/solver_factory.h"
#include "model/bending.h"
#include "model/collider_limits.h"
#include "model/collider_speed.h"
#include "model/errors.h"
#include "model/stability.h"
#include "model/vbd_local.h"
#include "scene/collider_validate.h"
#include "scene/params.h"
#include "scene/scene_loader.h"
#include "solver/instability.h"
#include "solver/step_control.h"

namespace cloth::app {
namespace {

constexpr const char* kHelp = R"(usage: clothsim validate SCENE [--set KEY.PATH=JSON]...
       clothsim validate --params-markdown

Checks SCENE (every key: type, range, unknown keys) and prints what it models: spring families,
forces, pins, colliders, integrator, every scalar parameter with its unit, the predicted stable
time step, and the GPU kernel variant.
Exit 0 if the scene is valid, 2 (with the file, key path and reason) if not.

--params-markdown prints the table of scalar parameters (key, unit, range, default, viewer
slider, meaning) as docs/parameters.md holds it, and needs no scene.
)";

std::string vec(const glm::dvec3& v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%g, %g, %g)", v.x, v.y, v.z);
    return buf;
}

std::string axisAngle(const AxisAngle& r) {
    char buf[120];
    std::snprintf(buf, sizeof buf, "%g° about %s", r.degrees, vec(r.axis).c_str());
    return buf;
}

std::string motionText(const ColliderMotion& m) {
    char buf[200];
    switch (m.type) {
        case MotionType::Rotation:
            std::snprintf(buf, sizeof buf, "turning %g °/s about %s through %s", m.degreesPerSecond,
                          vec(m.axis).c_str(), vec(m.pivot).c_str());
            break;
        case MotionType::Oscillation:
            std::snprintf(buf, sizeof buf, "oscillating %g m at %g Hz along %s (phase %g°)",
                          m.amplitude, m.frequency, vec(m.axis).c_str(), m.phaseDegrees);
            break;
        default:
            std::snprintf(buf, sizeof buf, "moving at %s m/s", vec(m.velocity).c_str());
    }
    return buf;
}

// One line per collider: its shape, then what docs/colliders.md §2–3 add to it.
// A moving collider also gets its step and its margin against docs/colliders.md §7's limit.
void printCollider(size_t n, const Collider& c, double dt) {
    std::string text;
    char buf[400];
    if (const Plane* p = c.as<Plane>()) {
        text = "plane through " + vec(p->point) + ", normal " + vec(p->normal);
    } else if (const Sphere* sp = c.as<Sphere>()) {
        std::snprintf(buf, sizeof buf, "sphere at %s, radius %g m", vec(sp->center).c_str(),
                      sp->radius);
        text = buf;
    } else if (const Box* b = c.as<Box>()) {
        text = "box at " + vec(b->center) + ", half extents " + vec(b->halfExtents) + " m, " +
               axisAngle(b->rotation);
    } else if (const Capsule* cap = c.as<Capsule>()) {
        std::snprintf(buf, sizeof buf, "capsule from %s to %s, radius %g m", vec(cap->a).c_str(),
                      vec(cap->b).c_str(), cap->radius);
        text = buf;
    } else if (const MeshCollider* m = c.as<MeshCollider>()) {
        const SdfGrid& g = m->baked->grid;
        std::snprintf(buf, sizeof buf,
                      "mesh %s (%zu triangles), SDF grid %d x %d x %d of %g m, band %g m, moved "
                      "by %s, %s",
                      m->file.c_str(), m->baked->mesh.triangles.size(), g.count.x, g.count.y,
                      g.count.z, g.cell, g.band, vec(m->translation).c_str(),
                      axisAngle(m->rotation).c_str());
        text = buf;
    }
    if (c.thickness != 0 || c.friction != 0) {
        std::snprintf(buf, sizeof buf, "; thickness %g m, friction %g", c.thickness, c.friction);
        text += buf;
    }
    if (c.motion) text += "; " + motionText(*c.motion);
    if (const double margin = motionStepMargin(c, dt); std::isfinite(margin)) {
        std::snprintf(buf, sizeof buf, "; %.3g m per step, %.3gx inside the tunnelling limit",
                      maxMotionSpeed(c) * dt, margin);
        text += buf;
    }
    std::printf("collider %zu   %s\n", n, text.c_str());
}

void printModel(const Scene& s) {
    const Grid g = s.grid();
    std::printf("scene        %s (%s)\n", s.name.c_str(), s.source.c_str());
    std::printf("cloth        %d x %d = %lld vertices, %g x %g m, spacing %.4g x %.4g m\n", g.nu,
                g.nv, (long long)g.count(), s.cloth.size.x, s.cloth.size.y, g.du, g.dv);
    std::printf("             origin %s, u axis %s, v axis %s\n", vec(g.origin).c_str(),
                vec(g.u).c_str(), vec(g.v).c_str());
    if (const std::optional<Material>& m = s.material) {
        // docs/physics.md "From a material to the grid": what the grid models of the fabric.
        const MembraneSprings k = membraneSprings(*m, g.du, g.dv);
        const double c =
            (m->stretch + std::sqrt(m->stretch * m->stretch + 4 * m->shear * m->shear)) / 2;
        std::printf(
            "material     %s: density %g kg/m^2, stretch %g N/m, shear %g N/m, bend %g N*m, "
            "air damping %g 1/s\n",
            m->preset.empty() ? "custom" : m->preset.c_str(), m->density, m->stretch, m->shear,
            m->bend, m->airDamping);
        std::printf(
            "mass         %.6g kg in all; %.4g kg per interior vertex, %.4g on an edge, "
            "%.4g at a corner\n",
            s.totalMass(), s.vertexMass(1, 1), s.vertexMass(1, 0), s.vertexMass(0, 0));
        std::printf(
            "springs      structural K = %.6g N/m along u, %.6g N/m along v; shear K = "
            "%.6g N/m; Poisson ratio %.3g (fixed by the lattice)\n",
            k.alongU, k.alongV, k.shear, m->shear / c);
        const BendingWeights w = bendingWeights(g, s.bendingStiffness());
        if (w.active())
            std::printf(
                "bending      B = %g N*m: energy weights %.4g N/m along u, %.4g along v, "
                "twist %.4g; bending length (B/(rho g))^(1/3) = %.3g m\n",
                m->bend, w.alongU, w.alongV, w.twist,
                std::cbrt(m->bend / (m->density * std::max(glm::length(s.gravity), 1e-300))));
        else
            std::printf("bending      not modelled\n");
        std::printf("forces       gravity %s m/s^2\n", vec(s.gravity).c_str());
        std::printf("             air drag c = %g 1/s%s\n", m->airDamping,
                    m->airDamping > 0 ? "" : " (not modelled)");
        if (Features::of(s).springDamping)  // docs/physics.md "Spring damping"
            std::printf(
                "             spring damping beta = %g s: a mode of omega decays at "
                "beta*omega^2/2\n",
                m->springDamping);
        else
            std::printf("             spring damping not modelled\n");
    } else {
        std::printf("mass         %g kg per vertex\n", s.cloth.mass);
        for (Family f : {Family::Structural, Family::Shear, Family::Bend}) {
            const double k = s.springs.of(f);
            if (k > 0)
                std::printf("springs      %-10s K = %g N/m\n", familyName(f), k);
            else
                std::printf("springs      %-10s not modelled\n", familyName(f));
        }
        std::printf("forces       gravity %s m/s^2\n", vec(s.gravity).c_str());
        std::printf("             damping mu = %g N*s/m%s\n", s.damping,
                    s.damping > 0 ? "" : " (not modelled)");
    }
    if (s.wind && s.wind->strength != 0)
        std::printf("             wind %s, K_w = %g %s\n", vec(s.wind->direction).c_str(),
                    s.wind->strength, s.material ? "N/m^2 (a pressure)" : "N");
    else
        std::printf("             wind not modelled\n");
    if (s.selfCollision)
        std::printf("contacts     self-collision, thickness %g m, friction %g\n",
                    s.selfCollision->thickness, s.selfCollision->friction);
    else
        std::printf("contacts     self-collision not modelled\n");
    if (s.pins.empty())
        std::printf("pins         none");
    else
        std::printf("pins         %zu:", s.pins.size());
    for (const Pin& p : s.pins) {
        std::printf(" (%d, %d)", p.i, p.j);
        if (p.follow >= 0) std::printf(" following colliders[%d]", p.follow);
    }
    std::printf("\n");
    if (s.colliders.empty()) std::printf("colliders    none\n");
    for (size_t n = 0; n < s.colliders.size(); ++n)
        printCollider(n, s.colliders[n], s.integrator.dt);
    std::printf("integrator   %s, dt = %g s, %d substeps per frame, duration %g s = %ld steps\n",
                methodName(s.integrator.method), s.integrator.dt, s.integrator.substeps, s.duration,
                s.defaultSteps());
    if (s.integrator.method == Method::ImplicitEuler)
        std::printf("             conjugate gradient, preconditioner %s\n",
                    preconditionerName(s.integrator.preconditioner));
    if (s.integrator.maxStepStrain > 0)
        std::printf(
            "step control a step that stretches a structural spring by more than %g of its "
            "rest length is taken again in halves, down to dt/%d\n",
            s.integrator.maxStepStrain, 1 << StepControl::kMaxHalvings);
    std::printf("max speed    %g m/s\n", s.maxSpeed);
}

// Every scalar of scene/params.cpp's table with the value in force, defaults included, so a key
// the file leaves out shows what the run will use.
void printParameters(const Scene& s) {
    const char* label = "parameters";
    for (const ParamSpec& p : paramTable()) {
        const std::optional<double> v = p.get ? p.get(s) : std::nullopt;
        if (!v) continue;
        std::printf("%-12s %s = %g%s%s\n", label, p.path, *v, p.unit[0] ? " " : "", p.unit);
        label = "";
    }
}

// Power iterations for validate's tight estimate of λ_max: each is one stencil pass.
constexpr int kPowerIterations = 40;

std::string formatDt(double dt) {
    if (std::isinf(dt)) return "any (unconditional)";
    if (dt <= 0) return "none";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g s", dt);
    return buf;
}

// Steps of the safe dt that 1/60 s of simulation needs: what real time costs at this bound.
std::string stepsPerFrame(double safeDt) {
    if (std::isinf(safeDt)) return "1";
    if (!(safeDt > 0)) return "-";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f", std::ceil((1.0 / 60) / safeDt));
    return buf;
}

void printStability(const Scene& s) {
    const StabilityBound b = estimateStability(s, kPowerIterations);
    const double bound = b.safeDt(s.integrator.method), dt = s.integrator.dt;
    std::printf("stability    lambda_max <= %.6g N/m (Gershgorin, DESIGN.md §2)\n", b.lambdaMax);
    std::printf("             lambda_max ~= %.6g N/m (%d power iterations at the initial state)\n",
                b.lambdaPower, kPowerIterations);
    if (b.springDamping > 0)  // docs/stability.md "Spring damping"
        std::printf(
            "             spring damping adds beta*omega_max^2 = %.4g 1/s to the stiffest "
            "mode's damping rate c = %g 1/s\n",
            b.springDamping * b.omega2Max, b.dampingRate);
    std::printf(
        "             largest stable dt   safe (Gershgorin)      tight (power)    steps per "
        "1/60 s frame\n");
    for (Method m : kMethods)
        std::printf("             %-18s  %-22s %-16s %-10s%s\n", methodName(m),
                    formatDt(b.safeDt(m)).c_str(), formatDt(b.tightDt(m)).c_str(),
                    stepsPerFrame(b.safeDt(m)).c_str(),
                    m == s.integrator.method ? "   <- the scene's" : "");
    if (std::isinf(bound))
        std::printf("             dt = %g s: %s has no stability bound\n", dt,
                    methodName(s.integrator.method));
    else if (dt < bound)
        std::printf("             dt = %g s is inside the bound (%.0f%% of it)\n", dt,
                    100 * dt / bound);
    else
        std::printf("             WARNING: dt = %g s exceeds the predicted bound: %s\n", dt,
                    stabilityAdvice(s).c_str());
    if (s.integrator.method == Method::Vbd) {  // its measured rule (solver/instability.h)
        const double rate = vbdSweepsPerSecond(s), held = vbdHoldingSweepsPerSecond(s);
        std::printf(
            "             vbd runs %.0f sweeps a simulated second (iterations / dt); a "
            "sheet this size dropped onto a collider held with %.0f "
            "(docs/performance.md)%s\n",
            rate, held, rate < held ? ": it may over-stretch where it lands on one" : "");
        const IntegratorSpec& in = s.integrator;
        const Grid g = s.grid();
        const VbdLevelsRun run =
            vbdLevelsRun(in.translationLevels, in.translationBlockWidth, g.nu, g.nv);
        if (run.levels > 0)
            std::printf(
                "             vbd runs %d translation levels (translation_levels = %d, "
                "translation_block_width = %d): the finest blocks %d x %d vertices, %d pass%s a "
                "step\n",
                run.levels, in.translationLevels, in.translationBlockWidth, run.width, run.height,
                in.translationLevelPasses, in.translationLevelPasses == 1 ? "" : "es");
    }
}

}  // namespace

int validateCommand(Args& args) {
    std::string path;
    std::vector<std::string> sets;
    while (!args.done()) {
        if (args.takeScene(path)) continue;
        const std::string f = args.flag();
        if (f == "--help") {
            std::fputs(kHelp, stdout);
            return kOk;
        }
        if (f == "--params-markdown") {
            std::fputs(paramsMarkdown().c_str(), stdout);
            return kOk;
        }
        if (f == "--set")
            addSet(sets, args.value(f));
        else
            args.unknown(f);
    }
    if (path.empty()) throw InputError("command line", "SCENE", "validate needs a scene file");
    const Scene scene = loadScene(path, sets);
    noteUnusedSettings(scene);
    printModel(scene);
    printParameters(scene);
    std::printf("features     %s\n", Features::of(scene).describe().c_str());
    printStability(scene);
    std::printf("gpu variant  %s\n", gpuVariant(scene, backendChoiceFromEnvironment().gpu).c_str());
    std::printf("valid\n");
    return kOk;
}

}  // namespace cloth::app
