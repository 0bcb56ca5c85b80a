// self_intersection.h's readObj: the OBJ frames the checker reads, parsed here on their own
// (v and f lines; everything else is skipped), with errors naming the file and line.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "reference/self_intersection.h"

namespace ref {
namespace {

[[noreturn]] void objError(const std::string& path, int line, const std::string& what) {
    throw std::runtime_error(path + ":" + std::to_string(line) + ": " + what);
}

bool parseDouble(const std::string& s, double& out) {
    char* end = nullptr;
    out = std::strtod(s.c_str(), &end);
    return end != s.c_str() && *end == '\0';
}

bool parseLong(const std::string& s, long& out) {
    char* end = nullptr;
    out = std::strtol(s.c_str(), &end, 10);
    return end != s.c_str() && *end == '\0';
}

// The 0-based vertex of a face corner `v`, `v/vt`, `v//vn` or `v/vt/vn`; the vt and vn parts
// may hold only digits and signs, so that a garbled corner is reported rather than half-read.
int cornerVertex(const std::string& corner, long vertexCount, const std::string& path, int line) {
    const size_t slash = std::min(corner.find('/'), corner.size());
    long index = 0;
    if (!parseLong(corner.substr(0, slash), index) || index == 0 ||
        std::count(corner.begin(), corner.end(), '/') > 2 ||
        corner.find_first_not_of("0123456789+-/", slash) != std::string::npos) {
        objError(path, line, "malformed face corner '" + corner + "'");
    }
    const long vertex = index > 0 ? index - 1 : vertexCount + index;  // negative: relative
    if (vertex < 0 || vertex >= vertexCount) {
        objError(path, line,
                 "vertex index " + std::to_string(index) + " out of range (" +
                     std::to_string(vertexCount) + " vertices read so far)");
    }
    return static_cast<int>(vertex);
}

}  // namespace

TriangleMesh readObj(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open");
    TriangleMesh mesh;
    std::string text;
    for (int line = 1; std::getline(in, text); ++line) {
        std::istringstream words(text.substr(0, text.find('#')));  // comments, also trailing
        std::string keyword;
        words >> keyword;
        std::vector<std::string> args;
        for (std::string word; words >> word;) args.push_back(word);
        if (keyword == "v") {
            // Beyond x y z, a w or an RGB colour (a common extension) must still be numbers.
            if (args.size() < 3) objError(path, line, "a vertex needs x, y and z");
            std::array<double, 3> p{};
            for (size_t k = 0; k < args.size(); ++k) {
                double value = 0;
                if (!parseDouble(args[k], value) || !std::isfinite(value)) {
                    objError(path, line, "bad vertex coordinate '" + args[k] + "'");
                }
                if (k < 3) p[k] = value;
            }
            mesh.positions.push_back(p);
        } else if (keyword == "f") {
            if (args.size() < 3) objError(path, line, "a face needs at least three corners");
            const long count = static_cast<long>(mesh.positions.size());
            std::vector<int> corners;
            for (const std::string& a : args) corners.push_back(cornerVertex(a, count, path, line));
            for (size_t i = 1; i + 1 < corners.size(); ++i) {
                mesh.triangles.push_back({corners[0], corners[i], corners[i + 1]});
            }
        }
    }
    return mesh;
}

}  // namespace ref
