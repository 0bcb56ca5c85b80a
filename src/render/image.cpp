#include "render/image.h"

#include <GL/glew.h>
#include <stb_image_write.h>

#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "model/output_file.h"

namespace cloth::render {
namespace {

constexpr int kSamples = 4;

}  // namespace

Image readPixels(int width, int height) {
    Image image{width, height, std::vector<std::uint8_t>(std::size_t(width) * height * 4)};
    std::vector<std::uint8_t> raw(image.rgba.size());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, raw.data());
    const std::size_t row = std::size_t(width) * 4;
    for (int y = 0; y < height; ++y)
        std::memcpy(&image.rgba[std::size_t(y) * row], &raw[std::size_t(height - 1 - y) * row],
                    row);
    for (std::size_t p = 3; p < image.rgba.size(); p += 4) image.rgba[p] = 255;  // opaque
    return image;
}

void writePng(const std::string& path, const Image& image) {
    OutputFile out(path);
    // stb encodes into memory and hands over the bytes in pieces; OutputFile checks each write.
    const auto append = [](void* context, void* data, int size) {
        static_cast<OutputFile*>(context)->write(data, std::size_t(size));
    };
    if (!stbi_write_png_to_func(append, &out, image.width, image.height, 4, image.rgba.data(),
                                image.width * 4))
        throw OutputError(path, "the PNG could not be encoded");
    out.commit();
}

OffscreenTarget::OffscreenTarget(int width, int height) : width_(width), height_(height) {
    glGenRenderbuffers(1, &colourMs_);
    glBindRenderbuffer(GL_RENDERBUFFER, colourMs_);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, kSamples, GL_RGBA8, width, height);
    glGenRenderbuffers(1, &depthMs_);
    glBindRenderbuffer(GL_RENDERBUFFER, depthMs_);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, kSamples, GL_DEPTH_COMPONENT24, width,
                                     height);
    glGenFramebuffers(1, &msFbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, msFbo_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colourMs_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depthMs_);
    const GLenum msStatus = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glGenRenderbuffers(1, &colour_);
    glBindRenderbuffer(GL_RENDERBUFFER, colour_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glGenFramebuffers(1, &resolveFbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, resolveFbo_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (msStatus != GL_FRAMEBUFFER_COMPLETE || status != GL_FRAMEBUFFER_COMPLETE) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "offscreen framebuffer %dx%d incomplete (0x%x, 0x%x)", width,
                      height, msStatus, status);
        throw std::runtime_error(buf);
    }
}

OffscreenTarget::~OffscreenTarget() {
    const GLuint fbos[] = {msFbo_, resolveFbo_};
    glDeleteFramebuffers(2, fbos);
    const GLuint rbs[] = {colourMs_, depthMs_, colour_};
    glDeleteRenderbuffers(3, rbs);
}

void OffscreenTarget::bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, msFbo_);
}

Image OffscreenTarget::read() const {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, msFbo_);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolveFbo_);
    glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, resolveFbo_);
    Image image = readPixels(width_, height_);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return image;
}

}  // namespace cloth::render
