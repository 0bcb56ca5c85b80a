// The positions in a CSV that `clothsim run --out-csv` wrote, for the command-line tests.
#pragma once

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace cloth::test {

// Rows i,j,x,y,z,... (DESIGN.md §5) in row order, positions only, each the double its digits
// name (scanf rounds as strtod does: the 17 digits of the double backend give its double back).
inline std::vector<std::array<double, 3>> readCsvPositions(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    std::vector<std::array<double, 3>> p;
    while (std::getline(in, line)) {
        int i, j;
        std::array<double, 3> x;
        if (std::sscanf(line.c_str(), "%d,%d,%lf,%lf,%lf", &i, &j, &x[0], &x[1], &x[2]) == 5)
            p.push_back(x);
    }
    return p;
}

}  // namespace cloth::test
