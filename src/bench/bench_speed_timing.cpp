#include "bench/bench_speed_timing.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <vector>

namespace cloth::app {

std::string cpuModel() {
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    return "unknown CPU";
}

std::uint64_t availableMemory() {
    std::ifstream in("/proc/meminfo");
    for (std::string key; in >> key;) {
        std::uint64_t kib = 0;
        in >> kib;
        if (key == "MemAvailable:") return kib * 1024;
        in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
    }
    return std::numeric_limits<std::uint64_t>::max();
}

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t m = v.size() / 2;
    return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

}  // namespace

Timing timeSteps(const std::function<bool(long)>& step, const std::function<double()>& device,
                 bool quick) {
    const double batchSeconds = quick ? 0.005 : 0.05, totalSeconds = quick ? 0.03 : 0.3;
    auto clock = [&](long n) {
        const auto t0 = std::chrono::steady_clock::now();
        if (!step(n)) throw BecameUnstable{};
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    };
    Timing t;
    clock(2);  // warm-up: first touch, shader compilation, thread start
    while (clock(t.stepsPerBatch) < batchSeconds && t.stepsPerBatch < (1L << 20))
        t.stepsPerBatch *= 2;
    std::vector<double> wall, dev;
    double total = 0;
    while (t.batches < 5 || (total < totalSeconds && t.batches < 200)) {
        const double s = clock(t.stepsPerBatch);
        total += s;
        wall.push_back(s / double(t.stepsPerBatch));
        dev.push_back(device());
        ++t.batches;
    }
    t.secondsPerStep = median(wall);
    t.deviceSecondsPerStep = median(dev);
    return t;
}

SpeedRow makeRow(int side, const std::string& target, const std::string& method, int threads,
                 const Timing& t, double minBytesPerVertex, double bandwidth) {
    SpeedRow r;
    r.side = side;
    r.vertices = long(side) * side;
    r.target = target;
    r.method = method;
    r.threads = threads;
    r.stepsPerBatch = t.stepsPerBatch;
    r.batches = t.batches;
    r.msPerStep = 1e3 * t.secondsPerStep;
    r.deviceMsPerStep = t.deviceSecondsPerStep > 0 ? 1e3 * t.deviceSecondsPerStep : NAN;
    r.stepsPerSecond = 1 / t.secondsPerStep;
    r.vertexStepsPerSecond = double(r.vertices) * r.stepsPerSecond;
    r.minBytesPerStep = minBytesPerVertex * double(r.vertices);
    r.achievedGBps = r.minBytesPerStep / t.secondsPerStep / 1e9;
    r.bandwidthFraction = bandwidth > 0 ? r.achievedGBps / bandwidth : NAN;
    r.peerRatio = NAN;
    return r;
}

}  // namespace cloth::app
