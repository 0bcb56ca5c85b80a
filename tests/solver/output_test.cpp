// Output files (DESIGN.md §5): the CSV round-trips, the OBJ is a consistent mesh whose faces
// wind about the written normals, and nothing non-finite or half-written ever reaches the disk.
#include "solver/output.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "scene/scene_loader.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;

std::string tempPath(const std::string& name) {
    return (fs::temp_directory_path() / ("clothsim_output_test_" + name)).string();
}

SimState bumpyState(int nu, int nv) {
    SimState s;
    s.nu = nu;
    s.nv = nv;
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            s.positions.push_back({0.1 * i + 1e-9 / 3, 0.05 * std::sin(i + 2.0 * j), 0.1 * j});
            s.velocities.push_back({1.0 / 3, -2.0 / 7, i * 1e-17});
        }
    return s;
}

TEST(Csv, DoubleValuesRoundTripExactly) {
    const SimState s = bumpyState(5, 3);
    const std::string path = tempPath("roundtrip.csv");
    writeCsv(path, s, Precision::Double);
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "i,j,x,y,z,vx,vy,vz");
    for (size_t k = 0; k < s.positions.size(); ++k) {
        ASSERT_TRUE(std::getline(in, line));
        int i, j;
        double x, y, z, vx, vy, vz;
        ASSERT_EQ(std::sscanf(line.c_str(), "%d,%d,%lf,%lf,%lf,%lf,%lf,%lf", &i, &j, &x, &y, &z,
                              &vx, &vy, &vz),
                  8);
        EXPECT_EQ(size_t(j * s.nu + i), k);  // index order k = j·nu + i
        EXPECT_EQ(x, s.positions[k].x);
        EXPECT_EQ(y, s.positions[k].y);
        EXPECT_EQ(z, s.positions[k].z);
        EXPECT_EQ(vx, s.velocities[k].x);
        EXPECT_EQ(vz, s.velocities[k].z);
    }
    EXPECT_FALSE(std::getline(in, line));
    fs::remove(path);
}

TEST(Csv, FloatValuesRoundTripThroughFloat) {
    SimState s = bumpyState(3, 2);
    for (auto& p : s.positions) p = glm::dvec3(glm::vec3(p));  // values a float solver holds
    const std::string path = tempPath("float.csv");
    writeCsv(path, s, Precision::Float);
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    std::getline(in, line);
    float x;
    ASSERT_EQ(std::sscanf(line.c_str(), "%*d,%*d,%f", &x), 1);
    EXPECT_EQ(x, float(s.positions[0].x));
    fs::remove(path);
}

TEST(Files, NonFiniteStateIsRefusedAndTheOldFileKept) {
    const std::string path = tempPath("keep.csv");
    { std::ofstream(path) << "previous\n"; }
    SimState s = bumpyState(2, 2);
    s.velocities[3].y = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(writeCsv(path, s, Precision::Double), std::runtime_error);
    EXPECT_THROW(writeObj(path, s, "x"), std::runtime_error);
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "previous");
    EXPECT_FALSE(fs::exists(path + ".tmp"));
    fs::remove(path);
}

TEST(Files, UnwritablePathThrowsWithTheName) {
    try {
        writeCsv("/nonexistent-dir/x.csv", bumpyState(2, 1), Precision::Double);
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.csv"), std::string::npos);
    }
}

struct Obj {
    std::vector<glm::dvec3> v, vn;
    std::vector<glm::dvec2> vt;
    std::vector<std::array<int, 3>> faces;  // 1-based, v = vt = vn index
    std::vector<std::string> lines;         // the `l` lines as written
};

Obj readObj(const std::string& path) {
    Obj o;
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream ss(line);
        std::string tag;
        ss >> tag;
        if (tag == "v" || tag == "vn") {
            glm::dvec3 p;
            ss >> p.x >> p.y >> p.z;
            (tag == "v" ? o.v : o.vn).push_back(p);
        } else if (tag == "vt") {
            glm::dvec2 t;
            ss >> t.x >> t.y;
            o.vt.push_back(t);
        } else if (tag == "f") {
            std::array<int, 3> f;
            for (int& idx : f) {
                std::string corner;
                ss >> corner;
                int a, b, c;
                EXPECT_EQ(std::sscanf(corner.c_str(), "%d/%d/%d", &a, &b, &c), 3);
                EXPECT_TRUE(a == b && b == c);
                idx = a;
            }
            o.faces.push_back(f);
        } else if (tag == "l") {
            o.lines.push_back(line);
        }
    }
    return o;
}

TEST(Obj, GridMeshHasTwoTrianglesPerCellWindingAboutTheNormals) {
    const Scene scene = parseScene(R"({"cloth": {"resolution": [7, 4], "size": [1.2, 0.6],
        "u_axis": [1, 0, 0], "v_axis": [0, 0, 1]}, "integrator": {"dt": 0.001}})",
                                   "obj");
    SimState s = bumpyState(7, 4);
    for (size_t k = 0; k < s.positions.size(); ++k)
        s.positions[k] = glm::dvec3(0.2 * (k % 7), 0.02 * std::sin(double(k)), 0.2 * (k / 7));
    const std::string path = tempPath("mesh.obj");
    writeObj(path, s, scene.name);
    const Obj o = readObj(path);
    ASSERT_EQ(o.v.size(), 28u);
    ASSERT_EQ(o.vt.size(), 28u);
    ASSERT_EQ(o.vn.size(), 28u);
    EXPECT_EQ(o.faces.size(), size_t(2 * 6 * 3));
    EXPECT_EQ(o.vt.front(), glm::dvec2(0, 0));
    EXPECT_EQ(o.vt.back(), glm::dvec2(1, 1));
    for (const auto& f : o.faces) {
        for (int idx : f) ASSERT_TRUE(idx >= 1 && idx <= 28);
        const glm::dvec3 n =
            glm::cross(o.v[f[1] - 1] - o.v[f[0] - 1], o.v[f[2] - 1] - o.v[f[0] - 1]);
        // Counter-clockwise seen from the vertex normal's side.
        EXPECT_GT(glm::dot(n, o.vn[f[0] - 1]), 0);
        EXPECT_NEAR(glm::length(o.vn[f[0] - 1]), 1.0, 1e-5);
    }
    fs::remove(path);
}

// One `l` per segment: Blender 3.4 imports a longer `l` as its first edge and drops the rest.
TEST(Obj, ChainIsOneLinePerSegmentWithoutFaces) {
    const std::string path = tempPath("chain.obj");
    writeObj(path, bumpyState(1, 3), "chain");
    const Obj o = readObj(path);
    EXPECT_EQ(o.v.size(), 3u);
    EXPECT_EQ(o.faces.size(), 0u);
    EXPECT_EQ(o.lines, (std::vector<std::string>{"l 1/1 2/2", "l 2/2 3/3"}));
    fs::remove(path);
}

}  // namespace
}  // namespace cloth
