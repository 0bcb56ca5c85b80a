// Looking at a rendered PNG in tests: load it (stb_image) and count pixels of the renderer's
// colours (src/render/renderer.cpp) inside a region.
#pragma once

#include <gtest/gtest.h>
#include <stb_image.h>

#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "support/gl_required.h"
#include "support/process.h"

namespace cloth::test {

struct Picture {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgb;
};

inline Picture loadPng(const std::string& path) {
    Picture p;
    int channels = 0;
    std::unique_ptr<unsigned char, void (*)(void*)> data(
        stbi_load(path.c_str(), &p.width, &p.height, &channels, 3), stbi_image_free);
    if (data) p.rgb.assign(data.get(), data.get() + std::size_t(p.width) * p.height * 3);
    return p;
}

// Colour classes, robust to lighting (a lit colour keeps its channel ratios).
inline bool clothFront(int r, int g, int b) {
    return r > 50 && r > 1.3 * g && g > 1.3 * b;
}
inline bool clothBack(int r, int g, int b) {
    return b > 50 && b > 1.3 * r && b > 1.2 * g;
}
inline bool sphereTeal(int r, int g, int b) {
    return g > 50 && g > 1.5 * r && g > 1.02 * b;
}
inline bool grey(int r, int g, int b) {
    return r > 45 && std::abs(r - g) < 12 && std::abs(g - b) < 12;
}

struct ColourCounts {
    long front = 0, back = 0, sphere = 0, grey = 0, distinct = 0, total = 0;
};

// Counts over the columns [x0, width) (the viewer's 3-D view is right of its panel).
inline ColourCounts countColours(const Picture& p, int x0 = 0) {
    ColourCounts c;
    std::vector<bool> seen(1 << 12);
    for (int y = 0; y < p.height; ++y) {
        for (int x = x0; x < p.width; ++x) {
            const std::uint8_t* q = &p.rgb[(std::size_t(y) * p.width + x) * 3];
            const int r = q[0], g = q[1], b = q[2];
            c.front += clothFront(r, g, b);
            c.back += clothBack(r, g, b);
            c.sphere += sphereTeal(r, g, b);
            c.grey += grey(r, g, b);
            seen[std::size_t((r >> 4) << 8 | (g >> 4) << 4 | (b >> 4))] = true;
            ++c.total;
        }
    }
    for (const bool s : seen) c.distinct += s;
    return c;
}

}  // namespace cloth::test
