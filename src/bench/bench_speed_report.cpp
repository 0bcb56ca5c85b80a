// bench speed's output: the CSV (header comments with the machine, the build and the traffic
// model), the same rows as JSON, a short table on stdout and the log-log plot (bench/speed.gp).
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "bench/bench.h"
#include "bench/bench_speed.h"
#include "bench/bench_speed_model.h"

namespace cloth::app {
namespace {

const std::vector<std::string> kColumns = {"size",
                                           "vertices",
                                           "target",
                                           "method",
                                           "features",
                                           "status",
                                           "dt",
                                           "threads",
                                           "steps_per_batch",
                                           "batches",
                                           "ms_per_step",
                                           "device_ms_per_step",
                                           "timing_source",
                                           "steps_per_s",
                                           "vertex_steps_per_s",
                                           "min_bytes_per_step",
                                           "achieved_GB_per_s",
                                           "bandwidth_fraction",
                                           "simulated_s_per_s",
                                           "speedup",
                                           "peer_ratio",
                                           "bytes_per_vertex",
                                           "gpu_variant",
                                           "gpu_dispatch",
                                           "forces_pass_ms",
                                           "integrate_pass_ms",
                                           "copy_ms"};

std::vector<std::string> cells(const SpeedRow& r) {
    return {std::to_string(r.side),
            std::to_string(r.vertices),
            r.target,
            r.method,
            r.features,
            r.status,
            cell(r.dt),
            std::to_string(r.threads),
            std::to_string(r.stepsPerBatch),
            std::to_string(r.batches),
            cell(r.msPerStep),
            cell(r.deviceMsPerStep),
            r.timingSource,
            cell(r.stepsPerSecond),
            cell(r.vertexStepsPerSecond),
            cell(r.minBytesPerStep),
            cell(r.achievedGBps),
            cell(r.bandwidthFraction),
            cell(r.stepsPerSecond * r.dt),
            cell(r.speedup),
            cell(r.peerRatio),
            cell(r.bytesPerVertex),
            r.variant,
            r.dispatch,
            cell(r.forcesPassMs),
            cell(r.integratePassMs),
            cell(r.copyMs)};
}

nlohmann::json number(double x) {
    return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json();
}

std::string csvText(const SpeedMeta& m, const std::vector<SpeedRow>& rows) {
    std::string s = "# clothsim bench speed: " + m.scene + (m.quick ? " (quick)" : "") + "\n";
    s += "# build " + m.buildType + "; cpu " + m.cpuModel + "; gpu " +
         (m.gpuRenderer.empty() ? "none" : m.gpuRenderer) + "\n";
    s += "# bandwidth: cpu triad " + cell(m.triadGBps) + " GB/s, gpu copy " + cell(m.copyGBps) +
         " GB/s (read + write bytes / best time)\n";
    s += std::string("# traffic model: ") + kTrafficModel + "\n";
    if (!m.peer.empty()) s += "# peer: " + m.peer + "\n";
    s += "# units: ms_per_step wall clock median batch [ms]; device_ms_per_step the GPU's own "
         "timing [ms]; vertex_steps_per_s [1/s]; min_bytes_per_step [B]; achieved_GB_per_s "
         "[1e9 B/s]; bandwidth_fraction of the triad (cpu, baseline) or copy (gpu); speedup over "
         "the baseline's vertex_steps_per_s at the same size; peer_ratio over the peer's; dt the "
         "step [s]; simulated_s_per_s simulated seconds per wall second; features declared (the "
         "scene) or all (plus inert copies of the features it lacks); bytes_per_vertex "
         "allocated [B]; gpu_variant work groups/forces kernel/dispatch asked; gpu_dispatch "
         "the dispatch run (auto resolved); forces_pass_ms, integrate_pass_ms, copy_ms one pass "
         "alone, copy over as many vec4 as vertices [ms]\n";
    s += join(kColumns, ',') + "\n";
    for (const SpeedRow& r : rows) s += join(cells(r), ',') + "\n";
    return s;
}

std::string jsonText(const SpeedMeta& m, const std::vector<SpeedRow>& rows) {
    nlohmann::json j;
    j["scene"] = m.scene;
    j["build_type"] = m.buildType;
    j["cpu_model"] = m.cpuModel;
    j["gpu_renderer"] = m.gpuRenderer;
    j["cpu_triad_GB_per_s"] = number(m.triadGBps);
    j["gpu_copy_GB_per_s"] = number(m.copyGBps);
    j["traffic_model"] = kTrafficModel;
    j["quick"] = m.quick;
    j["peer"] = m.peer;
    j["rows"] = nlohmann::json::array();
    for (const SpeedRow& r : rows) {
        nlohmann::json row;
        const auto c = cells(r);
        for (std::size_t i = 0; i < kColumns.size(); ++i) row[kColumns[i]] = c[i];
        for (const auto& [key, value] : {std::pair<const char*, double>{"ms_per_step", r.msPerStep},
                                         {"device_ms_per_step", r.deviceMsPerStep},
                                         {"steps_per_s", r.stepsPerSecond},
                                         {"vertex_steps_per_s", r.vertexStepsPerSecond},
                                         {"min_bytes_per_step", r.minBytesPerStep},
                                         {"achieved_GB_per_s", r.achievedGBps},
                                         {"bandwidth_fraction", r.bandwidthFraction},
                                         {"dt", r.dt},
                                         {"simulated_s_per_s", r.stepsPerSecond * r.dt},
                                         {"speedup", r.speedup},
                                         {"peer_ratio", r.peerRatio},
                                         {"bytes_per_vertex", r.bytesPerVertex},
                                         {"forces_pass_ms", r.forcesPassMs},
                                         {"integrate_pass_ms", r.integratePassMs},
                                         {"copy_ms", r.copyMs}})
            row[key] = number(value);
        for (const auto& [key, value] : {std::pair<const char*, long>{"size", r.side},
                                         {"vertices", r.vertices},
                                         {"threads", r.threads},
                                         {"steps_per_batch", r.stepsPerBatch},
                                         {"batches", r.batches}})
            row[key] = value;
        j["rows"].push_back(row);
    }
    return j.dump(2) + "\n";
}

void printTable(const SpeedMeta& m, const std::vector<SpeedRow>& rows) {
    std::printf("build %s | cpu %s | gpu %s\n", m.buildType.c_str(), m.cpuModel.c_str(),
                m.gpuRenderer.empty() ? "none" : m.gpuRenderer.c_str());
    if (std::isfinite(m.copyGBps))
        std::printf("bandwidth: cpu triad %.3g GB/s, gpu copy %.3g GB/s\n", m.triadGBps,
                    m.copyGBps);
    else  // no GPU target in this run
        std::printf("bandwidth: cpu triad %.3g GB/s\n", m.triadGBps);
    if (!m.peer.empty()) std::printf("peer: %s\n", m.peer.c_str());
    std::printf("%6s %-11s %-16s %-8s %10s %10s %12s %8s %6s %8s %7s %7s %s\n", "size", "target",
                "method", "features", "ms/step", "dev ms", "vtx-steps/s", "GB/s", "of bw",
                "speedup", "B/vtx", "vs peer", "variant");
    for (const SpeedRow& r : rows) {
        char device[16] = "-";  // CPU rows have no separate device time
        if (std::isfinite(r.deviceMsPerStep))
            std::snprintf(device, sizeof device, "%.4g", r.deviceMsPerStep);
        char peer[16] = "-";
        if (std::isfinite(r.peerRatio)) std::snprintf(peer, sizeof peer, "%.3gx", r.peerRatio);
        if (r.status != "ok") std::snprintf(peer, sizeof peer, "%s", r.status.c_str());
        char bandwidth[32];  // the peer has no traffic model: "-"
        std::snprintf(bandwidth, sizeof bandwidth, "%8s %6s", "-", "-");
        if (std::isfinite(r.achievedGBps))
            std::snprintf(bandwidth, sizeof bandwidth, "%8.3g %5.1f%%", r.achievedGBps,
                          100 * r.bandwidthFraction);
        std::printf("%6d %-11s %-16s %-8s %10.4g %10s %12.4g %s %7.2fx %7.1f %7s %s", r.side,
                    r.target.c_str(), r.method.c_str(), r.features.c_str(), r.msPerStep, device,
                    r.vertexStepsPerSecond, bandwidth, r.speedup, r.bytesPerVertex, peer,
                    r.variant.c_str());
        if (r.variant.size() >= 5 && r.variant.substr(r.variant.size() - 5) == "/auto")
            std::printf(" (%s)", r.dispatch.c_str());  // what auto chose
        if (std::isfinite(r.forcesPassMs))
            std::printf(" | forces %.4g ms, integrate %.4g ms, copy %.4g ms", r.forcesPassMs,
                        r.integratePassMs, r.copyMs);
        std::printf("\n");
    }
}

}  // namespace

void reportSpeed(const std::string& outDir, const SpeedMeta& meta,
                 const std::vector<SpeedRow>& rows) {
    const std::string stem = outputPath(outDir, "speed_" + meta.label);
    writeWholeFile(stem + ".csv", csvText(meta, rows));
    writeWholeFile(stem + ".json", jsonText(meta, rows));
    printTable(meta, rows);
    std::vector<std::string> series;
    for (const SpeedRow& r : rows) {
        const std::string id = r.target + ":" + r.method + ":" + r.features + ":" + r.variant;
        if (std::find(series.begin(), series.end(), id) == series.end()) series.push_back(id);
    }
    const auto plots = plot(meta.scriptDir, "speed.gp", stem,
                            {{"csv", stem + ".csv"},
                             {"series", join(series, ' ')},
                             {"title", "clothsim bench speed: " + meta.scene + " (" +
                                           meta.buildType + ", " + meta.cpuModel + ")"}});
    std::printf("wrote %s.csv, %s.json", stem.c_str(), stem.c_str());
    for (const std::string& p : plots) std::printf(", %s", p.c_str());
    std::printf("\n");
}

}  // namespace cloth::app
