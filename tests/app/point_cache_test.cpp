// `run --out-pc2 FILE --every K`: a point cache (PC2) that Blender's Mesh Cache modifier plays on
// the OBJ at rest written beside it. The file is read back byte by byte, little-endian whatever the
// host: the 32-byte header (signature, version 1, point count, start frame 0, sample rate 1, sample
// count) and every sample, against the CSV of a run stopped at the sample's step (exact in
// float32: the double backend's CSV carries 17 digits, which give back the very double the solver
// held, and float() of it is the float the cache holds) and, for the initial sample, the OBJ at
// rest. Bad outputs are exit 2 before the run, and a run that stops short leaves the previous
// cache as it was.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "support/csv_positions.h"
#include "support/process.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
using test::runProcess;

const std::string kExe = CLOTH_EXE;
const std::string kDrape = CLOTH_SOURCE_DIR "/scenes/drape.json";
constexpr int kNu = 7, kNv = 5;  // not square, so an i/j swap in the vertex order shows

// drape.json made small: kNu × kNv vertices, Δt = 1 ms (inside its bound), quiet.
std::vector<std::string> smallDrape(std::vector<std::string> extra) {
    std::vector<std::string> argv = {kExe,    "run",
                                     kDrape,  "--quiet",
                                     "--set", "cloth.resolution=[7, 5]",
                                     "--set", "integrator.dt=1e-3"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    return argv;
}

std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// A little-endian 32-bit word at `at`, assembled byte by byte.
std::uint32_t wordAt(const std::string& bytes, size_t at) {
    std::uint32_t w = 0;
    for (int b = 3; b >= 0; --b) w = (w << 8) | std::uint8_t(bytes.at(at + size_t(b)));
    return w;
}

float floatAt(const std::string& bytes, size_t at) {
    return std::bit_cast<float>(wordAt(bytes, at));
}

struct Pc2 {
    std::string signature;  // the first 12 bytes
    std::int32_t version = 0, points = 0, samples = 0;
    float start = -1, rate = -1;
    std::vector<std::vector<std::array<float, 3>>> positions;  // [sample][vertex]
};

Pc2 readPc2(const fs::path& path) {
    const std::string bytes = slurp(path);
    Pc2 c;
    if (bytes.size() < 32) {
        ADD_FAILURE() << path << " has " << bytes.size() << " bytes, less than a header";
        return c;
    }
    c.signature = bytes.substr(0, 12);
    c.version = std::int32_t(wordAt(bytes, 12));
    c.points = std::int32_t(wordAt(bytes, 16));
    c.start = floatAt(bytes, 20);
    c.rate = floatAt(bytes, 24);
    c.samples = std::int32_t(wordAt(bytes, 28));
    EXPECT_EQ(bytes.size(), 32 + size_t(c.samples) * size_t(c.points) * 12) << path;
    for (size_t at = 32; at + size_t(c.points) * 12 <= bytes.size();) {
        auto& sample = c.positions.emplace_back();
        for (int k = 0; k < c.points; ++k, at += 12)
            sample.push_back({floatAt(bytes, at), floatAt(bytes, at + 4), floatAt(bytes, at + 8)});
    }
    return c;
}

// The OBJ's `v`, `vt`, `f` and `l` lines: positions as printed, lines as written, and how many
// of the others.
struct ObjCounts {
    std::vector<std::array<double, 3>> v;
    std::vector<std::string> l;
    int vt = 0, f = 0;
};

ObjCounts readObj(const fs::path& path) {
    std::ifstream in(path);
    ObjCounts o;
    for (std::string line; std::getline(in, line);) {
        std::istringstream s(line);
        std::string tag;
        s >> tag;
        if (tag == "v") s >> o.v.emplace_back()[0] >> o.v.back()[1] >> o.v.back()[2];
        if (tag == "l") o.l.push_back(line);
        o.vt += tag == "vt";
        o.f += tag == "f";
    }
    return o;
}

// Whether `got` is `want` rounded to float32, or within `ulps` floats of it.
bool sameFloat(float got, double want, int ulps = 0) {
    float lo = float(want), hi = float(want);
    for (int n = 0; n < ulps; ++n) {
        lo = std::nextafter(lo, -INFINITY);
        hi = std::nextafter(hi, INFINITY);
    }
    return got >= lo && got <= hi;
}

// Law: the header says PC2 version 1, the cloth's vertex count, start frame 0, one frame per
// sample and the sample count; there is a sample at step 0 and every K steps, and none for a last
// partial interval (as --frames writes no frame for it); each sample is the solver's state in
// float32, in the vertex order of the OBJ at rest written beside the cache.
TEST(PointCache, HeaderAndEverySampleMatchTheStateAtItsStep) {
    const fs::path d = test::freshTempDir("point_cache_test", "samples");
    const int every = 20, steps = 50;  // samples at steps 0, 20, 40
    const auto r = runProcess(
        smallDrape({"--steps", std::to_string(steps), "--every", std::to_string(every), "--out-pc2",
                    (d / "cache.pc2").string(), "--frames", (d / "frames").string()}),
        120);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);

    const Pc2 c = readPc2(d / "cache.pc2");
    EXPECT_EQ(c.signature, std::string("POINTCACHE2\0", 12));
    EXPECT_EQ(c.version, 1);
    EXPECT_EQ(c.points, kNu * kNv);
    EXPECT_EQ(c.start, 0.0f);
    EXPECT_EQ(c.rate, 1.0f);
    ASSERT_EQ(c.samples, steps / every + 1);
    ASSERT_EQ(c.positions.size(), size_t(c.samples));
    // The OBJ frames of the same run are at the same steps.
    EXPECT_EQ(std::distance(fs::directory_iterator(d / "frames"), fs::directory_iterator()),
              c.samples);

    // Sample 0 is the OBJ at rest, whose `v` lines carry 9 digits of the double: rounded to
    // float that is the float the cache holds or, when the double lies within 1e-9 of halfway
    // between two floats, its neighbour (two roundings), hence one float of slack here only.
    const ObjCounts obj = readObj(d / "cache.obj");
    ASSERT_EQ(obj.v.size(), size_t(kNu * kNv));
    EXPECT_EQ(obj.vt, kNu * kNv);                 // UVs, one per vertex
    EXPECT_EQ(obj.f, 2 * (kNu - 1) * (kNv - 1));  // two triangles per cell
    for (size_t k = 0; k < obj.v.size(); ++k)
        for (int a = 0; a < 3; ++a)
            EXPECT_TRUE(sameFloat(c.positions[0][k][a], obj.v[k][a], 1))
                << "sample 0, vertex " << k << ", axis " << a << ": " << c.positions[0][k][a]
                << " against " << obj.v[k][a];

    // Sample s against a run stopped at step s·K: exactly float(x) of its CSV's x.
    for (int s = 1; s < c.samples; ++s) {
        const fs::path csv = d / ("step" + std::to_string(s * every) + ".csv");
        const auto stopped = runProcess(
            smallDrape({"--steps", std::to_string(s * every), "--out-csv", csv.string()}), 120);
        ASSERT_EQ(stopped.exitCode, 0) << test::describe(stopped);
        const auto p = test::readCsvPositions(csv);
        ASSERT_EQ(p.size(), size_t(kNu * kNv));
        int mismatches = 0;
        for (size_t k = 0; k < p.size(); ++k)
            for (int a = 0; a < 3; ++a)
                if (!sameFloat(c.positions[size_t(s)][k][a], p[k][a]) && ++mismatches <= 5)
                    ADD_FAILURE() << "sample " << s << " (step " << s * every << "), vertex " << k
                                  << ", axis " << a << ": " << c.positions[size_t(s)][k][a]
                                  << " against float(" << p[k][a] << ")";
        EXPECT_EQ(mismatches, 0) << "sample " << s;
    }
    // The cloth moved: the samples are not one state repeated.
    EXPECT_NE(c.positions[0], c.positions.back());
}

// Law: without --every, a sample per displayed frame: every integrator.substeps steps, as the
// summary says.
TEST(PointCache, WithoutEveryASamplePerDisplayedFrame) {
    const fs::path d = test::freshTempDir("point_cache_test", "substeps");
    auto argv = smallDrape({"--steps", "100", "--set", "integrator.substeps=30", "--out-pc2",
                            (d / "cache.pc2").string()});
    argv.erase(argv.begin() + 3);  // not --quiet: the summary names the files
    const auto r = runProcess(argv, 120);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_EQ(readPc2(d / "cache.pc2").samples, 4);  // steps 0, 30, 60, 90
    EXPECT_NE(r.out.find("(4 samples of 35 points, one every 30 steps) and " +
                         (d / "cache.obj").string()),
              std::string::npos)
        << r.out;
}

// Law: Blender (where it is on PATH; else the test skips) imports the OBJ at rest, and its Mesh
// Cache modifier, format PC2 and otherwise at its defaults, plays the cache on it: every frame f
// it evaluates is sample f to the bit (tests/data/pc2_in_blender.py).
TEST(PointCache, BlenderPlaysItOnTheObj) {
    if (std::system("command -v blender >/dev/null 2>&1") != 0)
        GTEST_SKIP() << "blender is not on PATH";
    const fs::path d = test::freshTempDir("point_cache_test", "blender");
    const auto r = runProcess(
        smallDrape({"--steps", "100", "--every", "10", "--out-pc2", (d / "cache.pc2").string()}),
        120);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    const auto b =
        runProcess({"/usr/bin/env", "blender", "-b", "--factory-startup", "--python-exit-code", "2",
                    "-P", CLOTH_SOURCE_DIR "/tests/data/pc2_in_blender.py", "--",
                    (d / "cache.obj").string(), (d / "cache.pc2").string()},
                   300);
    EXPECT_EQ(b.exitCode, 0) << test::describe(b);
    EXPECT_NE(b.out.find("imported 35 vertices of 35 points"), std::string::npos) << b.out;
    EXPECT_NE(b.out.find("largest difference: 0.0 played, 0.0 from Frame Start 1"),
              std::string::npos)
        << b.out;
}

// Law: a 1×N chain's cache has its N points, and its OBJ at rest all N vertices, as N − 1
// segments of one `l` each: Blender 3.4's importer makes one edge of a longer `l` and drops the
// rest, and then refuses the cache ("vertex count mismatch").
TEST(PointCache, ChainObjHasEverySegment) {
    const fs::path d = test::freshTempDir("point_cache_test", "chain");
    const auto r =
        runProcess({kExe, "run", CLOTH_SOURCE_DIR "/scenes/chain.json", "--quiet", "--steps", "20",
                    "--every", "10", "--out-pc2", (d / "chain.pc2").string()},
                   60);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    const Pc2 c = readPc2(d / "chain.pc2");
    EXPECT_EQ(c.points, 3);
    EXPECT_EQ(c.samples, 3);
    const ObjCounts obj = readObj(d / "chain.obj");
    EXPECT_EQ(obj.v.size(), 3u);
    EXPECT_EQ(obj.l, (std::vector<std::string>{"l 1/1 2/2", "l 2/2 3/3"}));
}

// Law: an output that cannot be written, a cache whose OBJ would land on itself or on --out-obj
// or beside a device, and --every 0 or without an output are exit 2 naming the flag, before
// anything is written.
TEST(PointCache, BadOutputsAreInvalidInputAndWriteNothing) {
    const fs::path d = test::freshTempDir("point_cache_test", "bad");
    fs::create_directories(d / "dir.pc2");
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"--out-pc2", (d / "missing" / "cache.pc2").string()}, "--out-pc2"},
        {{"--out-pc2", (d / "dir.pc2").string()}, "--out-pc2"},
        {{"--out-pc2", (d / "cache.obj").string()}, "--out-pc2"},
        {{"--out-pc2", (d / "a.pc2").string(), "--out-obj", (d / "a.obj").string()}, "--out-pc2"},
        {{"--out-pc2", (d / "cache.pc2").string(), "--every", "0"}, "--every"},
        {{"--every", "5"}, "--every"},
        {{"--out-pc2", "/dev/null"}, "is a device"},  // its OBJ would be made as /dev/null.obj
    };
    for (const auto& [extra, flag] : cases) {
        auto args = extra;
        args.insert(args.begin(), {"--steps", "10"});
        const auto r = runProcess(smallDrape(args), 60);
        EXPECT_EQ(r.exitCode, 2) << extra[1] << ": " << test::describe(r);
        EXPECT_NE(r.err.find("invalid input"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(flag), std::string::npos) << r.err;
    }
    // Only the folder the test made: no cache, no OBJ, no temporary file.
    EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 1);
    EXPECT_FALSE(fs::exists("/dev/null.obj"));
}

// Law: a run that becomes unstable writes no cache and no OBJ, keeps the previous cache as it
// was and leaves no temporary file.
TEST(PointCache, UnstableRunKeepsThePreviousCache) {
    const fs::path d = test::freshTempDir("point_cache_test", "unstable");
    { std::ofstream(d / "cache.pc2") << "previous\n"; }
    const auto r = runProcess({kExe, "run", kDrape, "--quiet", "--set", "cloth.resolution=[7, 5]",
                               "--set", "integrator.dt=0.05", "--steps", "400", "--every", "10",
                               "--out-pc2", (d / "cache.pc2").string()},
                              120);
    EXPECT_EQ(r.exitCode, 3) << test::describe(r);
    EXPECT_NE(r.err.find("nor the point cache"), std::string::npos) << r.err;
    EXPECT_EQ(slurp(d / "cache.pc2"), "previous\n");
    EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 1);
}

}  // namespace
}  // namespace cloth
