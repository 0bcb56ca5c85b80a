// The self-intersection oracle's OBJ reader (reference/self_intersection.h readObj): every corner
// form a face line takes, negative indices, comments and CRLF; bad input named by file and line.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "reference/self_intersection.h"
#include "support/process.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
using ref::TriangleMesh;
using V3 = std::array<double, 3>;

fs::path writeFile(const std::string& name, const std::string& text) {
    const fs::path path = test::testTempDir() / name;
    std::ofstream(path) << text;
    return path;
}

std::string readError(const fs::path& path) {
    try {
        ref::readObj(path.string());
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(SelfIntersection, ReadObjTakesEveryCornerForm) {
    const fs::path path = writeFile("good.obj",
                                    "# a comment\n"
                                    "o sheet\n"
                                    "v 0 0 0\n"
                                    "v 1 0 0  # trailing comment\n"
                                    "v 1 1 0\r\n"
                                    "v 0 1 0.5 1.0\n"
                                    "vt 0 0\nvn 0 0 1\n"
                                    "f 1/1/1 2/2/2 3/3/3\n"
                                    "f 1//1 2//1 3//1 4//1\n"
                                    "l 1 2\n"
                                    "s off\n"
                                    "f -4/1 -3/1 -1/1\n"
                                    "f 2 3 4\n");
    const TriangleMesh m = ref::readObj(path.string());
    ASSERT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.positions[3], (V3{0, 1, 0.5}));
    const std::vector<std::array<int, 3>> expected{
        {0, 1, 2}, {0, 1, 2}, {0, 2, 3}, {0, 1, 3}, {1, 2, 3}};
    EXPECT_EQ(m.triangles, expected);
}

TEST(SelfIntersection, ReadObjNamesFileAndLineOfBadInput) {
    const fs::path bad = writeFile("bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    const std::string message = readError(bad);
    EXPECT_NE(message.find(bad.string() + ":4"), std::string::npos) << message;
    EXPECT_NE(message.find("out of range"), std::string::npos) << message;
    for (const char* text :
         {"v 0 0\n", "v 0 0 zero\n", "v 0 0 nan\n", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n",
          "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 0 2\n", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n",
          "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2/x 3\n", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n"}) {
        const fs::path path = writeFile("bad.obj", text);
        EXPECT_NE(readError(path).find(path.string() + ":"), std::string::npos) << text;
    }
    EXPECT_NE(readError("/nonexistent/clothsim.obj").find("/nonexistent/clothsim.obj"),
              std::string::npos);
}

}  // namespace
}  // namespace cloth
