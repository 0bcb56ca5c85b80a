// Export a 3D artist can use: `run --frames DIR --every K` writes OBJ frames
// whose names sort in step order; each frame, read back by tinyobjloader (an independent
// parser), has one v, vt and vn per vertex equal to the solver's state, the UVs of the grid,
// the normals of DESIGN.md §2 and 2(nu−1)(nv−1) faces; `--out-colliders` writes the scene's
// colliders as their own objects with the right bounds; `render --frames` writes a PNG sequence.
#include <gtest/gtest.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "support/csv_positions.h"
#include "support/process.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
using test::readCsvPositions;
using test::runProcess;

const std::string kExe = CLOTH_EXE;
const std::string kDrape = CLOTH_SOURCE_DIR "/scenes/drape.json";

struct Obj {
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
};

Obj readObj(const fs::path& path) {
    Obj o;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    EXPECT_TRUE(tinyobj::LoadObj(&o.attrib, &o.shapes, &materials, &warn, &err, path.c_str()))
        << err;
    return o;
}

std::array<double, 3> diff(const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

// DESIGN.md §2's vertex normal, written out again: a = p(i+1) − p(i−1), b = p(j+1) − p(j−1),
// clamped at the borders, n = a × b / |a × b|.
std::array<double, 3> normalAt(const std::vector<std::array<double, 3>>& p, int nu, int nv, int i,
                               int j) {
    const auto at = [&](int ii, int jj) { return p[size_t(jj) * nu + ii]; };
    const auto a = diff(at(std::min(i + 1, nu - 1), j), at(std::max(i - 1, 0), j));
    const auto b = diff(at(i, std::min(j + 1, nv - 1)), at(i, std::max(j - 1, 0)));
    std::array<double, 3> n{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                            a[0] * b[1] - a[1] * b[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double& c : n) c /= len;
    return n;
}

// Law: frame names sort in step order; each frame has one v/vt/vn per vertex equal to the
// state (CSV), the grid's UVs, DESIGN.md §2 normals and two triangles per cell.
TEST(Export, ObjFramesSortInStepOrderAndMatchTheSolverState) {
    const fs::path dir = test::freshTempDir("export_test", "frames");
    const int nu = 7, nv = 5, every = 40, steps = 200;
    const auto r =
        runProcess({kExe, "run", kDrape, "--steps", std::to_string(steps), "--quiet", "--set",
                    "cloth.resolution=[7, 5]", "--set", "integrator.dt=1e-3", "--frames",
                    (dir / "f").string(), "--every", std::to_string(every), "--out-csv",
                    (dir / "final.csv").string(), "--out-obj", (dir / "final.obj").string()},
                   120);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir / "f")) names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());  // lexicographic, as a file browser sorts
    ASSERT_EQ(names.size(), size_t(steps / every + 1));
    for (size_t k = 0; k < names.size(); ++k) {
        char want[64];
        std::snprintf(want, sizeof want, "drape_%06zu.obj", k * every);
        EXPECT_EQ(names[k], want) << "frame names sort in step order";
    }
    // The last frame and --out-obj are the final state the CSV holds.
    const auto csv = readCsvPositions(dir / "final.csv");
    ASSERT_EQ(csv.size(), size_t(nu * nv));
    for (const fs::path& path : {dir / "f" / names.back(), dir / "final.obj"}) {
        const Obj o = readObj(path);
        ASSERT_EQ(o.attrib.vertices.size(), size_t(3 * nu * nv));
        ASSERT_EQ(o.attrib.normals.size(), size_t(3 * nu * nv));
        ASSERT_EQ(o.attrib.texcoords.size(), size_t(2 * nu * nv));
        ASSERT_EQ(o.shapes.size(), 1u);
        EXPECT_EQ(o.shapes[0].mesh.num_face_vertices.size(), size_t(2 * (nu - 1) * (nv - 1)));
        for (int j = 0; j < nv; ++j)
            for (int i = 0; i < nu; ++i) {
                const size_t k = size_t(j) * nu + i;
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(o.attrib.vertices[3 * k + c], csv[k][c],
                                1e-8 * (1 + std::abs(csv[k][c])));
                const auto n = normalAt(csv, nu, nv, i, j);
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(o.attrib.normals[3 * k + c], n[c], 2e-6);
                EXPECT_NEAR(o.attrib.texcoords[2 * k], double(i) / (nu - 1), 1e-9);
                EXPECT_NEAR(o.attrib.texcoords[2 * k + 1], double(j) / (nv - 1), 1e-9);
            }
        // Every face corner names the same v, vt and vn (one attribute set per grid vertex).
        for (const tinyobj::index_t& idx : o.shapes[0].mesh.indices) {
            EXPECT_EQ(idx.vertex_index, idx.texcoord_index);
            EXPECT_EQ(idx.vertex_index, idx.normal_index);
        }
    }
}

// The colliders' OBJ: one object per collider; the plane is a square of half size
// max(10, 4·extent) on y = 0, the sphere's vertices lie on the sphere (centre (0, 0.5, 0),
// radius 0.35), so its bounds are the sphere's to the icosphere's chord error.
TEST(Export, CollidersObjReadsBackWithTheRightBounds) {
    const fs::path dir = test::freshTempDir("export_test", "colliders");
    const fs::path file = dir / "colliders.obj";
    const auto r = runProcess(
        {kExe, "run", kDrape, "--steps", "1", "--quiet", "--out-colliders", file.string()}, 60);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    const Obj o = readObj(file);
    ASSERT_EQ(o.shapes.size(), 2u);
    EXPECT_EQ(o.shapes[0].name, "collider0_plane");
    EXPECT_EQ(o.shapes[1].name, "collider1_sphere");
    const auto bounds = [&](const tinyobj::shape_t& s) {
        std::array<double, 6> b{INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
        for (const tinyobj::index_t& idx : s.mesh.indices)
            for (int c = 0; c < 3; ++c) {
                const double x = o.attrib.vertices[3 * size_t(idx.vertex_index) + c];
                b[c] = std::min(b[c], x);
                b[3 + c] = std::max(b[3 + c], x);
            }
        return b;
    };
    const auto plane = bounds(o.shapes[0]);
    EXPECT_EQ(o.shapes[0].mesh.num_face_vertices.size(), 2u);
    EXPECT_NEAR(plane[1], 0, 1e-9);
    EXPECT_NEAR(plane[4], 0, 1e-9);
    EXPECT_NEAR(plane[0], -10, 1e-6);
    EXPECT_NEAR(plane[3], 10, 1e-6);
    const auto sphere = bounds(o.shapes[1]);
    const double c[3] = {0, 0.5, 0};
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(sphere[a], c[a] - 0.35, 0.35 * 0.02);
        EXPECT_NEAR(sphere[3 + a], c[a] + 0.35, 0.35 * 0.02);
    }
    for (size_t k = 0; k < o.shapes[1].mesh.indices.size(); ++k) {
        const size_t v = size_t(o.shapes[1].mesh.indices[k].vertex_index);
        const double x = o.attrib.vertices[3 * v], y = o.attrib.vertices[3 * v + 1] - 0.5,
                     z = o.attrib.vertices[3 * v + 2];
        EXPECT_NEAR(std::sqrt(x * x + y * y + z * z), 0.35, 1e-7);
    }
}

// Law: --frames without --every is invalid input (exit 2).
TEST(Export, RunFramesWithoutEveryIsAnInputError) {
    const auto r = runProcess({kExe, "run", kDrape, "--frames", "/tmp/x"}, 30);
    EXPECT_EQ(r.exitCode, 2) << test::describe(r);
}

// The rows of an --out-solves file after its header line (returned in `header`).
struct SolveRow {
    long step = 0, iterations = 0;
    double residual = 0;
    int converged = 0;
};
std::vector<SolveRow> readSolveRows(const fs::path& csv, std::string& header) {
    std::ifstream in(csv);
    std::getline(in, header);
    std::vector<SolveRow> rows;
    std::string line;
    while (std::getline(in, line)) {
        SolveRow r;
        EXPECT_EQ(std::sscanf(line.c_str(), "%ld,%ld,%lf,%d", &r.step, &r.iterations, &r.residual,
                              &r.converged),
                  4)
            << line;
        rows.push_back(r);
    }
    return rows;
}

// --out-solves writes one row per implicit step: its CG iterations, final |r|/|b| (at most the
// tolerance where it converged) and the flag; the rows add up to run's summary. An integrator
// without a linear system refuses the flag as invalid input.
TEST(Export, OutSolvesHasARowPerImplicitStepThatSumsToTheSummary) {
    const fs::path csv = fs::temp_directory_path() / "clothsim_solves_test.csv";
    fs::remove(csv);
    const auto r =
        runProcess({kExe, "run", kDrape, "--steps", "300", "--set",
                    "integrator.method=\"implicit_euler\"", "--set", "integrator.dt=0.016667",
                    "--set", "integrator.preconditioner=\"jacobi\"", "--out-solves", csv.string()},
                   60);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    std::string header;
    long rows = 0, iterations = 0;
    for (const SolveRow& row : readSolveRows(csv, header)) {
        EXPECT_EQ(row.step, ++rows);
        EXPECT_EQ(row.converged, 1) << "step " << row.step;
        EXPECT_LE(row.residual, 1e-5) << "step " << row.step;
        iterations += row.iterations;
    }
    EXPECT_EQ(header, "step,iterations,residual,converged");
    EXPECT_EQ(rows, 300);  // run steps in chunks of total/100 without --out-solves
    char average[64];
    std::snprintf(average, sizeof average, "%.1f iterations on average", double(iterations) / 300);
    EXPECT_NE(r.out.find(average), std::string::npos) << r.out;
    fs::remove(csv);

    const auto refused = runProcess({kExe, "run", kDrape, "--out-solves", csv.string()}, 30);
    EXPECT_EQ(refused.exitCode, 2) << test::describe(refused);
    EXPECT_NE(refused.err.find("--out-solves"), std::string::npos) << refused.err;
    EXPECT_FALSE(fs::exists(csv));
}

// With the step control splitting every step, a row still stands for one step of the scene's Δt
// and counts the iterations of all its solves: the rows sum to the summary's total.
TEST(Export, OutSolvesCountsEverySolveOfASplitStep) {
    const fs::path csv = fs::temp_directory_path() / "clothsim_solves_split_test.csv";
    fs::remove(csv);
    const auto r =
        runProcess({kExe, "run", kDrape, "--steps", "30", "--set",
                    "integrator.method=\"implicit_euler\"", "--set", "integrator.dt=0.016667",
                    "--set", "integrator.max_step_strain=1e-9", "--out-solves", csv.string()},
                   60);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    std::string header;
    long rows = 0, iterations = 0;
    for (const SolveRow& row : readSolveRows(csv, header)) {
        EXPECT_EQ(row.step, ++rows);
        iterations += row.iterations;
    }
    EXPECT_EQ(rows, 30);
    long solves = 0;
    const std::size_t at = r.out.find("implicit solve: ");
    ASSERT_NE(at, std::string::npos) << r.out;
    ASSERT_EQ(std::sscanf(r.out.c_str() + at, "implicit solve: %ld CG solves", &solves), 1)
        << r.out;
    EXPECT_GT(solves, 30 * 8) << "the steps were not split";
    char average[64];
    std::snprintf(average, sizeof average, "%.1f iterations on average",
                  double(iterations) / double(solves));
    EXPECT_NE(r.out.find(average), std::string::npos) << r.out;
    fs::remove(csv);
}

}  // namespace
}  // namespace cloth
