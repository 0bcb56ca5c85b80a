// clothsim bench speed: its options from the command line, then bench/bench_speed.h runs it.
#include <cstdio>
#include <filesystem>

#include "app/bench_flags.h"
#include "app/cli.h"
#include "bench/bench_peer.h"
#include "bench/bench_speed.h"
#include "model/errors.h"

namespace cloth::app {
namespace {

using Options = SpeedOptions;

constexpr const char* kHelp = R"(usage: clothsim bench speed [SCENE] [options]

Times the scene (default scenes/hanging.json: 1 m x 1 m of denim hanging from two corners)
resized to each size x size grid on every backend asked for (the CPU in float and double, the
GPU in float) and on the baseline: the seed's explicit Euler loop, one thread, double, the 1x
line of the speed-ups. A material resized is the same cloth, finer: each size steps at the
share of its own stability bound that the scene's dt has at the scene's resolution (unless
--set integrator.dt=... fixes it), so larger sizes take shorter steps; compare
simulated_s_per_s across sizes. bench/hanging_per_vertex.json is the seed's per-vertex cloth
(the same K and mass per vertex at every size: a larger size is a heavier, stiffer cloth). After warm-up steps, a batch of steps is sized to about 50 ms and
repeated until 0.3 s and 5 batches have passed; the median batch is reported. The CPU's triad
bandwidth and the GPU's copy-kernel bandwidth are measured in the same run; achieved GB/s
counts the bytes a step must move at least (read and write each vertex's position and
velocity).

options:
  --sizes LIST        grid sides, comma-separated (default 32,64,...,4096: the default sizes
                      that do not fit in memory, or on the GPU, are skipped with the reason;
                      a listed size that does not fit is refused)
  --backend cpu|gpu|both   where to run (default both; without a GPU, both means cpu)
  --methods LIST      integrators, comma-separated, or all (default the scene's)
  --set KEY.PATH=JSON override a scene key (repeatable)
  --out DIR           output folder (default bench/results)
  --label NAME        file names speed_NAME.csv/.json/.png/.svg (default the scene's name)
  --threads N         CPU threads (default automatic)
  --features declared|all|both
                      time the scene as declared (default), with every feature it does not
                      declare added inert (wind of strength 1e-30, spring families of stiffness
                      1e-30, a plane and a sphere 1000 extents away: the same motion, every code
                      path compiled in and run), or both; rows say which in 'features'
  --peer bullet       also time Bullet's btSoftBody on the same cloth (same links, masses,
                      pins, gravity, dt; stiffness and damping mapped, see docs/performance.md)
                      at sizes up to 512 (default sizes 64,128,256), checked not to explode;
                      a per-vertex scene only (default bench/hanging_per_vertex.json)
  --peer-dt SECONDS   the peer's step, with its stiffness and damping mapped at that step
                      (default the scene's dt); compare simulated_s_per_s then
  --workgroups LIST   GPU work-group shapes WXxWY, comma-separated (default 16x16); every GPU
                      row is labelled with its variant (shape/forces/dispatch)
  --gpu-forces LIST   global, tiled or both: where the GPU's forces pass reads the neighbours'
                      positions, straight from the buffer or from a shared-memory tile (default
                      global)
  --gpu-dispatch LIST auto, per-step, many-steps, comma-separated: two dispatches per step, or
                      many steps in one work-group dispatch (explicit/symplectic Euler); auto
                      picks many-steps up to 24x24 on llvmpipe, 64x64 on hardware (default
                      auto); many-steps rows use neither the shape nor the tile
  --check-every N     GPU steps between reads of the instability flag (default 64)
  --pass-times        GPU rows also time one forces pass, one integrate pass and the copy
                      kernel over as many vec4 as the grid has vertices, each alone
  --quick             short timing (5 ms batches, 30 ms per run, small bandwidth arrays)
  --allow-debug       run in a Debug build (refused otherwise: its timings mean nothing)
  --help              this text
)";

// Returns false when --help was asked for.
bool parse(Args& args, Options& o) {
    while (!args.done()) {
        if (args.takeScene(o.scenePath)) continue;
        const std::string f = args.flag();
        if (f == "--help" || f == "-h") return false;
        if (parseCommonFlag(f, args, o) || parseGpuSweepFlag(f, args, o.gpuSweep)) continue;
        if (f == "--sizes") {
            o.sizes = parseSizes(f, args.value(f));
            o.sizesGiven = true;
        } else if (f == "--features") {
            o.features = parseFeatureSet(f, args.value(f));
        } else if (f == "--peer") {
            o.peer = args.value(f);
            if (const auto why = peerUnavailable(o.peer)) throw InputError("command line", f, *why);
        } else if (f == "--peer-dt") {
            o.peerDt = parsePositive(f, args.value(f));
        } else if (f == "--allow-debug") {
            o.allowDebug = true;
        } else {
            args.unknown(f);
        }
    }
    if (o.peerDt > 0 && o.peer.empty())
        throw InputError("command line", "--peer-dt", "sets the peer's step: give --peer too");
    if (!o.peer.empty() && !o.sizesGiven) o.sizes = {64, 128, 256};
    // The peer maps the per-vertex form (cloth.mass, springs, damping): its default is the
    // seed's cloth.
    const std::filesystem::path bench = benchScriptDir(o.scriptDir);
    if (o.scenePath.empty())
        o.scenePath = (o.peer.empty() ? bench.parent_path() / "scenes" / "hanging.json"
                                      : bench / "hanging_per_vertex.json")
                          .string();
    return true;
}

}  // namespace

int benchSpeedCommand(Args& args) {
    return benchSubcommand<Options>(args, kHelp, parse, runBenchSpeed);
}

}  // namespace cloth::app
