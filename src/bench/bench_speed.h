// `clothsim bench speed`: its options (app/cmd_bench_speed.cpp reads them from the command line),
// its rows and their output (bench_speed.cpp measures, bench_speed_report.cpp writes the CSV, the
// JSON, the table and the plot).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "bench/bench.h"
#include "bench/bench_features.h"
#include "bench/bench_speed_gpu.h"

namespace cloth::app {

// One measured run: a backend (or the baseline) at one size.
struct SpeedRow {
    int side = 0;  // the grid is side × side
    long vertices = 0;
    std::string target;  // "baseline", "cpu_float", "cpu_double", "gpu_float", "peer_bullet"
    std::string method;
    std::string features = "declared";  // or "all": the scene plus inert other features
    std::string status = "ok";          // "exploded": a peer's run that blew up (not timed)
    double dt = 0;                      // the step [s]
    int threads = 0;
    long stepsPerBatch = 0;
    int batches = 0;
    double msPerStep = 0;        // wall clock, median batch
    double deviceMsPerStep = 0;  // the GPU's own timing (NaN for the CPU)
    std::string timingSource;    // "GL timer query", "wall clock", "" for the CPU
    double stepsPerSecond = 0;
    double vertexStepsPerSecond = 0;
    double minBytesPerStep = 0;  // the traffic model (bench_speed_model.h)
    double achievedGBps = 0;
    double bandwidthFraction = 0;  // of the triad (CPU) or the copy kernel (GPU)
    double speedup = 0;            // vertex-steps/s over the baseline's at this size
    double bytesPerVertex = 0;     // allocated by the backend
    double peerRatio = 0;          // vertex-steps/s over the peer's at this size (NaN: no peer)
    std::string variant;   // GPU as asked: shape/forces/dispatch, "16x16/global/auto"; "" CPU
    std::string dispatch;  // GPU: the dispatch that ran, "per-step" or "many-steps"; "" CPU
    // GPU with --pass-times: one forces pass, one integrate pass, the copy kernel over as many
    // vec4 as vertices, each alone [ms]; NaN otherwise.
    double forcesPassMs = NAN, integratePassMs = NAN, copyMs = NAN;
};

struct SpeedMeta {
    std::string scene, label, buildType, cpuModel, gpuRenderer;
    std::string peer;  // the peer's model as run (PeerCloth::describe), "" without --peer
    double triadGBps = 0, copyGBps = 0;  // NaN when not measured
    bool quick = false;
    std::string scriptDir;  // BenchCommonOptions::scriptDir
};

// Writes DIR/speed_LABEL.csv and .json, the plot (when gnuplot is there) and the table on stdout.
void reportSpeed(const std::string& outDir, const SpeedMeta& meta,
                 const std::vector<SpeedRow>& rows);

struct SpeedOptions : BenchCommonOptions {  // methods empty: the scene's
    std::vector<int> sizes{32, 64, 128, 256, 512, 1024, 2048, 4096};
    bool sizesGiven = false, allowDebug = false;
    FeatureSet features = FeatureSet::Declared;
    std::string peer;          // "" or "bullet"
    double peerDt = 0;         // [s]; 0: the scene's
    GpuSweepOptions gpuSweep;  // --workgroups, --gpu-forces, --gpu-dispatch, ...
};

// Runs the bench and writes its CSV and plots; returns the exit code.
int runBenchSpeed(const SpeedOptions& options);

}  // namespace cloth::app
