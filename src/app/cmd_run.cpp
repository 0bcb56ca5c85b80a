// clothsim run SCENE [options]: a headless simulation (DESIGN.md §5).
#include <sys/stat.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>

#include "app/backend_flags.h"
#include "app/cli.h"
#include "app/progress.h"
#include "app/reports.h"
#include "backends/solver_factory.h"
#include "model/collider_mesh.h"
#include "model/errors.h"
#include "model/output_file.h"
#include "model/stability.h"
#include "scene/scene_loader.h"
#include "solver/output.h"

namespace cloth::app {
namespace {

constexpr const char* kHelp = R"(usage: clothsim run SCENE [options]

Simulates SCENE headless for its "duration" (or --steps) and reports the speed.

options:
  --backend cpu|gpu|auto    solver backend (default cpu); auto: the GPU when its OpenGL device
                            is hardware, else the CPU (a software rasteriser such as llvmpipe
                            runs the GPU backend about 10-30x slower), said on stderr
  --precision float|double  CPU arithmetic (default double; the GPU computes in float)
  --threads N               CPU threads (default: automatic by cloth size)
  --steps N                 number of steps (default: duration / integrator.dt)
  --set KEY.PATH=JSON       override a scene key, validated like the file (repeatable),
                            e.g. --set integrator.dt=0.002 --set springs.bend=0
  --out-csv FILE            final state: i,j,x,y,z,vx,vy,vz, one row per vertex
  --out-obj FILE            final frame as Wavefront OBJ (positions, normals, UVs, faces)
  --frames DIR --every K    an OBJ every K steps (and the initial one) into DIR, named
                            SCENE_<step>.obj with the step zero-padded so the names sort
  --out-pc2 FILE            a point cache (PC2) of the positions at step 0 and every K steps
                            (--every K, shared with --frames, and like it none for a last
                            partial interval; default K: the scene's integrator.substeps, one
                            sample per displayed frame), and beside it the cloth at rest with
                            UVs as OBJ, in the same vertex order (FILE with .obj for .pc2): in
                            Blender, import that OBJ and add a Mesh Cache modifier, format PC2,
                            on it (the header says start frame 0, one frame per sample)
  --out-colliders FILE      the colliders as their own OBJ, one object each (a plane as a
                            square of side 8× the cloth's extent, at least 20 m)
  --out-solves FILE         implicit_euler: one row per step, step,iterations,residual,converged
                            (the final |r|/|b| of its conjugate gradient)
  --quiet                   print nothing but errors
  --help                    this text

exit codes: 0 ok, 1 internal error or a failed write, 2 invalid input (an output path
            that cannot be written included), 3 unstable, 4 GPU unavailable
)";

struct RunOptions {
    std::string scenePath;
    BackendChoice backend = backendChoiceFromEnvironment();
    bool doubleAsked = false;  // --precision double: --backend auto picks the CPU
    long steps = 0;            // 0: the scene's duration
    std::vector<std::string> sets;
    std::string csv, obj, framesDir, colliders, solves, pc2;
    long every = 0;  // --every; for --out-pc2 alone, 0 until the scene's substeps fill it in
    bool quiet = false;
};

// Returns false when --help was asked for.
bool parse(Args& args, RunOptions& o) {
    RunFlags common{o.backend, o.sets};
    while (!args.done()) {
        if (args.takeScene(o.scenePath)) continue;
        const std::string f = args.flag();
        if (f == "--help") return false;
        if (common.take(f, args)) continue;
        if (f == "--steps")
            o.steps = args.positiveInt(f);
        else if (f == "--out-csv")
            o.csv = args.value(f);
        else if (f == "--out-obj")
            o.obj = args.value(f);
        else if (f == "--frames")
            o.framesDir = args.value(f);
        else if (f == "--out-pc2")
            o.pc2 = args.value(f);
        else if (f == "--out-colliders")
            o.colliders = args.value(f);
        else if (f == "--out-solves")
            o.solves = args.value(f);
        else if (f == "--every")
            o.every = args.positiveInt(f);
        else if (f == "--quiet")
            o.quiet = true;
        else
            args.unknown(f);
    }
    if (o.scenePath.empty()) throw InputError("command line", "SCENE", "run needs a scene file");
    common.finish(o.quiet);
    o.doubleAsked = common.doubleAsked();
    if (!o.framesDir.empty() && o.every == 0)
        throw InputError("command line", "--every", "--frames DIR needs --every K");
    if (o.framesDir.empty() && o.pc2.empty() && o.every > 0)
        throw InputError("command line", "--every",
                         "--every K needs --frames DIR or --out-pc2 FILE");
    return true;
}

// The OBJ at rest that --out-pc2 FILE writes beside it: FILE with .obj for its extension.
std::string pc2ObjPath(const std::string& pc2) {
    return std::filesystem::path(pc2).replace_extension(".obj").string();
}

// --out-pc2's two files checked before the run, as every output is (exit 2), and its writer
// opened for the run's samples: the initial state and every K steps up to `total`.
std::optional<Pc2Writer> openPc2(const RunOptions& o, const Scene& scene, long total) {
    if (o.pc2.empty()) return std::nullopt;
    const std::string obj = pc2ObjPath(o.pc2);
    if (obj == o.pc2 || obj == o.obj)
        throw InputError("command line", "--out-pc2",
                         "'" + o.pc2 + "' would write its OBJ at rest to '" + obj + "', which " +
                             (obj == o.pc2 ? "is the point cache itself" : "--out-obj names") +
                             "; name the cache FILE.pc2");
    checkOutputFile("--out-pc2", o.pc2);
    checkOutputFile("--out-pc2", obj);
    struct stat st {};
    if (::stat(o.pc2.c_str(), &st) == 0 && S_ISCHR(st.st_mode))  // /dev/null: OBJ in /dev
        throw InputError("command line", "--out-pc2",
                         "'" + o.pc2 +
                             "' is a device: the cache's OBJ at rest would be made "
                             "beside it as '" +
                             obj + "'; name a file");
    const long samples = total / o.every + 1;
    if (samples > std::numeric_limits<std::int32_t>::max())
        throw InputError("command line", "--every",
                         std::to_string(total) + " steps make " + std::to_string(samples) +
                             " samples, more than a PC2 file counts (2^31 - 1)");
    return std::optional<Pc2Writer>(std::in_place, o.pc2, long(scene.cloth.nu) * scene.cloth.nv,
                                    samples);
}

std::string framePath(const RunOptions& o, const Scene& scene, long step, long total) {
    const int digits = std::max<int>(6, int(std::to_string(total).size()));
    char name[64];
    std::snprintf(name, sizeof name, "_%0*ld.obj", digits, step);
    return (std::filesystem::path(o.framesDir) / (scene.name + name)).string();
}

// --out-solves: the rows of each step's conjugate-gradient solve, written when the run ends (an
// unstable run's too, up to its last step).
struct SolveLog {
    explicit SolveLog(std::string file) : path(std::move(file)) {}
    std::string path, rows = "step,iterations,residual,converged\n";
    bool wanted() const { return !path.empty(); }
    SolveStats before;  // the counts at the last row
    // A step's iterations are those of all its solves: one, or, where the step control split
    // the step, every piece's and every thrown-away try's. It converged if none missed.
    void add(long step, const SolveStats& s) {
        char row[96];
        std::snprintf(row, sizeof row, "%ld,%ld,%.9g,%d\n", step, s.iterations - before.iterations,
                      s.lastResidual, s.misses == before.misses ? 1 : 0);
        rows += row;
        before = s;
    }
    void write() const {
        if (wanted()) writeWholeFile(path, rows);
    }
};

// Seconds a run spent [s]: in all, stepping alone (frames not written), and on the device.
struct RunTimes {
    double wall = 0, stepping = 0, device = 0;
};

// What the run writes at step 0 and every K steps (--every): an OBJ frame into --frames DIR, a
// sample into --out-pc2 FILE.
void writeEvery(const RunOptions& o, const Scene& scene, const SimState& state, long step,
                long total, std::optional<Pc2Writer>& pc2) {
    if (!o.framesDir.empty()) writeObj(framePath(o, scene, step, total), state, scene.name);
    if (pc2) pc2->add(state);
}

// The run's final files as asked: CSV, OBJ, the colliders' OBJ, and the point cache with its OBJ
// at rest (`initial`), the OBJ first: a cache is put in place only beside the mesh it plays on.
void writeFinalFiles(const RunOptions& o, const Scene& scene, const SimState& state,
                     const SimState& initial, std::optional<Pc2Writer>& pc2) {
    if (!o.csv.empty()) writeCsv(o.csv, state, effectivePrecision(o.backend));
    if (!o.obj.empty()) writeObj(o.obj, state, scene.name);
    if (!o.colliders.empty())  // at their pose at t = 0 (a moving collider where it starts)
        writeMeshesObj(o.colliders,
                       colliderMeshes(scene.colliders, std::max(10.0, 4 * scene.grid().extent())));
    if (pc2) {
        writeObj(pc2ObjPath(o.pc2), initial, scene.name);
        pc2->commit();
    }
}

// The summary line (README, "The command line"), the GPU's time and the solves, files written.
void printSummary(const RunOptions& o, const Scene& scene, const Solver& solver, long total,
                  const RunTimes& t) {
    const double vertexSteps = double(scene.cloth.nu) * double(scene.cloth.nv) * double(total);
    std::printf("%s: %ld steps, %.4g s simulated, %.3f s wall, %.3g vertex-steps/s (%s)\n",
                scene.name.c_str(), total, solver.time(), t.wall, vertexSteps / t.stepping,
                solver.name().c_str());
    if (t.device > 0)
        std::printf("gpu time %.4g ms/step (%s), %.3g vertex-steps/s of GPU time\n",
                    1e3 * t.device / double(total), solver.deviceReport().timing.c_str(),
                    vertexSteps / t.device);
    const SolveStats& cg = solver.solveStats();
    if (cg.solves > 0)
        std::printf(
            "implicit solve: %ld CG solves (preconditioner %s), %.1f iterations on average, at "
            "most %d\n",
            cg.solves, preconditionerName(scene.integrator.preconditioner),
            double(cg.iterations) / double(cg.solves), cg.mostIterations);
    const SelfCollisionStats self = solver.selfCollisionStats();
    if (self.steps > 0)
        std::printf(
            "self-collision: %.2f substeps per step (at most %d; %ld steps over the cap), %.2f "
            "iterations per substep, %.1f contacts per iteration\n",
            double(self.substeps) / double(self.steps), self.mostSubsteps, self.stepsOverBound,
            double(self.iterations) / double(self.substeps),
            self.iterations ? double(self.contacts) / double(self.iterations) : 0.0);
    const StepControlStats control = solver.stepControlStats();
    if (Features::of(scene).stepControl)
        std::printf(
            "step control: %ld of %ld steps split (max_step_strain %g), %ld tries rejected, %ld "
            "substeps kept, the shortest dt/%d\n",
            control.split, total, scene.integrator.maxStepStrain, control.rejected,
            control.substeps, 1 << control.deepest);
    for (const std::string* f : {&o.csv, &o.obj, &o.colliders})
        if (!f->empty()) std::printf("wrote %s\n", f->c_str());
    if (!o.pc2.empty())
        std::printf("wrote %s (%ld samples of %d points, one every %ld steps) and %s (at rest)\n",
                    o.pc2.c_str(), total / o.every + 1, scene.cloth.nu * scene.cloth.nv, o.every,
                    pc2ObjPath(o.pc2).c_str());
    if (!o.solves.empty()) std::printf("wrote %s\n", o.solves.c_str());
    if (!o.framesDir.empty())
        std::printf("wrote %ld frames to %s\n", total / o.every + 1, o.framesDir.c_str());
}

}  // namespace

int runCommand(Args& args) {
    RunOptions o;
    if (!parse(args, o)) {
        std::fputs(kHelp, stdout);
        return kOk;
    }
    const Scene scene = loadScene(o.scenePath, o.sets);
    checkOutputFile("--out-csv", o.csv);
    checkOutputFile("--out-obj", o.obj);
    checkOutputFile("--out-colliders", o.colliders);
    checkOutputFile("--out-solves", o.solves);
    checkDistinctFiles({{"SCENE", o.scenePath},
                        {"--out-csv", o.csv},
                        {"--out-obj", o.obj},
                        {"--out-pc2", o.pc2},
                        {"--out-pc2's OBJ at rest", o.pc2.empty() ? "" : pc2ObjPath(o.pc2)},
                        {"--out-colliders", o.colliders},
                        {"--out-solves", o.solves}});
    if (!o.solves.empty() && scene.integrator.method != Method::ImplicitEuler)
        throw InputError("command line", "--out-solves",
                         std::string("the scene's integrator ") +
                             methodName(scene.integrator.method) +
                             " solves no linear system; --out-solves needs implicit_euler");
    SolveLog solveLog{o.solves};
    if (!o.framesDir.empty()) prepareFramesDir("--frames", o.framesDir);
    const long total = o.steps > 0 ? o.steps : scene.defaultSteps();
    if (o.every == 0 && !o.pc2.empty()) o.every = std::max(1, scene.integrator.substeps);
    std::optional<Pc2Writer> pc2 = openPc2(o, scene, total);
    settleBackendAndSay(o.backend, scene, o.doubleAsked, o.quiet);
    std::unique_ptr<Solver> solver = makeSolver(scene, o.backend);
    if (!o.quiet) {
        noteUnusedSettings(scene);
        warnUnstableDt(scene);
    }

    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    RunTimes times;
    // Read only when something is written every K steps: a large grid's state is large.
    const SimState initial = o.every > 0 ? solver->read() : SimState{};
    if (o.every > 0) writeEvery(o, scene, initial, 0, total, pc2);
    Progress progress(total, !o.quiet);
    const long checkEvery = strainCheckSteps(scene.integrator.dt);
    const long chunk = std::max(1L, std::min(total / 100, checkEvery));
    long checked = 0;  // steps done at the last strain check
    while (solver->stepsDone() < total) {
        long n = std::min(chunk, total - solver->stepsDone());
        if (o.every > 0) n = std::min(n, o.every - solver->stepsDone() % o.every);
        // The strain is checked every checkEvery steps exactly, as the Python module and the
        // renderer check it: the same run is unstable or not whatever the progress' chunks.
        n = std::min(n, checked + checkEvery - solver->stepsDone());
        if (solveLog.wanted()) n = 1;  // a row per step
        const auto t0 = Clock::now();
        StepResult r = solver->step(n);
        times.stepping += std::chrono::duration<double>(Clock::now() - t0).count();
        times.device += solver->deviceReport().secondsPerStep * double(r.stepsTaken);
        if (!r.unstable && strainCheckDue(checked, solver->stepsDone(), total, checkEvery)) {
            if (auto strained = strainInstability(scene, *solver, checked)) r = *strained;
            checked = solver->stepsDone();
        }
        if (r.unstable) {
            progress.finish();
            solveLog.write();
            reportUnstable(scene, *solver, r,
                           pc2 ? "nothing was written for the unstable state, nor the point cache"
                               : "nothing was written for the unstable state");
            return kUnstable;
        }
        if (solveLog.wanted()) solveLog.add(solver->stepsDone(), solver->solveStats());
        if (o.every > 0 && solver->stepsDone() % o.every == 0)
            writeEvery(o, scene, solver->read(), solver->stepsDone(), total, pc2);
        progress.update(solver->stepsDone());
    }
    times.wall = std::chrono::duration<double>(Clock::now() - start).count();
    progress.finish();

    reportSolveMisses(scene, *solver);
    writeFinalFiles(o, scene, solver->read(), initial, pc2);
    solveLog.write();
    if (!o.quiet) printSummary(o, scene, *solver, total, times);
    return kOk;
}

}  // namespace cloth::app
