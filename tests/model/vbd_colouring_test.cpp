// Vertex Block Descent's colouring c = (i + 2j) mod 5 (docs/integrators.md): no energy term of the
// model, a spring of the 12-neighbour stencil, a bending second difference or a twist cell, joins
// two vertices of one colour, and the colours split the grid evenly. The same checks reject
// (i + j) mod 5, which gives the diagonal (1, −1) one colour.
#include "model/vbd_colouring.h"

#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "model/grid.h"

namespace cloth {
namespace {

using Colouring = std::function<int(int, int)>;

// The groups of vertices each energy term couples on an nu × nv grid.
std::vector<std::vector<std::array<int, 2>>> energyTerms(int nu, int nv) {
    std::vector<std::vector<std::array<int, 2>>> terms;
    auto inside = [&](int i, int j) { return i >= 0 && i < nu && j >= 0 && j < nv; };
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            for (const SpringOffset& o : kSpringOffsets)
                if (inside(i + o.di, j + o.dj)) terms.push_back({{i, j}, {i + o.di, j + o.dj}});
            if (inside(i - 1, j) && inside(i + 1, j))
                terms.push_back({{i - 1, j}, {i, j}, {i + 1, j}});
            if (inside(i, j - 1) && inside(i, j + 1))
                terms.push_back({{i, j - 1}, {i, j}, {i, j + 1}});
            if (inside(i + 1, j + 1))
                terms.push_back({{i, j}, {i + 1, j}, {i, j + 1}, {i + 1, j + 1}});
        }
    return terms;
}

// The first energy term with two vertices of one colour, or "".
std::string conflict(const Colouring& colour, int nu, int nv) {
    for (const auto& term : energyTerms(nu, nv))
        for (std::size_t a = 0; a < term.size(); ++a)
            for (std::size_t b = a + 1; b < term.size(); ++b)
                if (colour(term[a][0], term[a][1]) == colour(term[b][0], term[b][1])) {
                    std::ostringstream out;
                    out << "(" << term[a][0] << ", " << term[a][1] << ") and (" << term[b][0]
                        << ", " << term[b][1] << ")";
                    return out.str();
                }
    return "";
}

TEST(VbdColouring, NoEnergyTermJoinsTwoVerticesOfOneColour) {
    for (const SpringOffset& o : kSpringOffsets)
        EXPECT_NE(0, ((o.di + 2 * o.dj) % 5 + 5) % 5) << o.di << ", " << o.dj;
    for (auto [nu, nv] : {std::array<int, 2>{2, 2}, {13, 11}, {40, 7}})
        EXPECT_EQ("", conflict(vbdColour, nu, nv)) << nu << " x " << nv;
    // The check has teeth: (i + j) mod 5 colours the diagonal (1, −1) alike.
    EXPECT_NE("", conflict([](int i, int j) { return (i + j) % 5; }, 13, 11));
}

TEST(VbdColouring, TheFiveColoursSplitTheGridEvenly) {
    const int nu = 64, nv = 48;
    std::array<int, kVbdColours> count{};
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) ++count[std::size_t(vbdColour(i, j))];
    for (int c : count) EXPECT_NEAR(c, nu * nv / 5.0, nv) << "a colour's share";
}

}  // namespace
}  // namespace cloth
