// Pixels read back from a framebuffer, and PNG output (stb_image_write).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace cloth::render {

struct Image {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;  // top row first, 4 bytes per pixel
};

// Reads the bound read framebuffer's (0, 0, width, height) and flips it so the top row comes
// first (GL's rows start at the bottom).
Image readPixels(int width, int height);

// Writes `image` as PNG through model/output_file.h (a regular file replaced whole, a symlink's
// target, a FIFO written through). Throws OutputError naming the file when it cannot be written.
void writePng(const std::string& path, const Image& image);

// An offscreen framebuffer with 4× multisampling, resolved when read.
class OffscreenTarget {
public:
    OffscreenTarget(int width, int height);  // needs a current GL context
    ~OffscreenTarget();
    OffscreenTarget(const OffscreenTarget&) = delete;
    OffscreenTarget& operator=(const OffscreenTarget&) = delete;

    void bind() const;  // as the draw framebuffer, viewport not set
    Image read() const;
    int width() const { return width_; }
    int height() const { return height_; }

private:
    int width_, height_;
    unsigned msFbo_ = 0, resolveFbo_ = 0;
    unsigned colourMs_ = 0, depthMs_ = 0, colour_ = 0;
};

}  // namespace cloth::render
