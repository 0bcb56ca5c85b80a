// The headless OpenGL context the GPU backend computes in (DESIGN.md §3: a GL 4.3+ context, no
// window). One per process, made on first use: EGL's device platform (a hardware device
// preferred; gpuSetup().eglDevice picks one), else Mesa's surfaceless platform, else the
// default display. A GL context already current on the calling thread (the viewer's window) is
// adopted instead, so the solver's buffers live where the renderer draws.
#pragma once

#include <array>
#include <string>

namespace cloth {

// What the context offers; the compute limits decide work-group sizes and the largest grid.
struct GpuInfo {
    std::string platform;    // "EGL device 0 (hardware)", "EGL surfaceless (Mesa)", ...
    std::string eglDevices;  // every EGL device: "0 (software), 1 (hardware)"; empty if none
    std::string eglVendor;   // empty for an adopted context
    std::string eglVersion;
    std::string renderer;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string vendor;    // GL_VENDOR
    std::string version;   // GL_VERSION
    std::string glslVersion;
    int glMajor = 0, glMinor = 0;
    std::array<int, 3> maxWorkGroupCount{};  // per dimension of a dispatch
    std::array<int, 3> maxWorkGroupSize{};   // local size per dimension
    int maxInvocations = 0;                  // local size product
    int maxSharedMemory = 0;                 // [bytes]
    long long maxStorageBlockSize = 0;       // one SSBO binding [bytes]
    long long maxUniformBlockSize = 0;       // one uniform block (gpu::Params) [bytes]
    int maxComputeStorageBlocks = 0;         // storage blocks one compute shader may use (≥ 8)
    bool timerQueries = false;               // GL_TIME_ELAPSED has bits
    bool software = false;                   // a CPU rasteriser (llvmpipe, softpipe, swrast)

    std::string describe() const;  // multi-line, for `clothsim info`
};

// Whether GL_RENDERER names a CPU rasteriser (llvmpipe, softpipe, swrast, SwiftShader).
bool softwareRenderer(const std::string& renderer);

class GlContext {
public:
    // The process-wide context, made current on the calling thread. Throws GpuUnavailable.
    static GlContext& instance();

    const GpuInfo& info() const { return info_; }
    // Makes the context current again if someone else's is (no-op for an adopted context).
    void makeCurrent() const;

    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

private:
    GlContext();
    void createEgl();
    void loadFunctions();
    void queryInfo();

    void* display_ = nullptr;  // EGLDisplay, EGLContext, EGLSurface: void* keeps EGL out of
    void* context_ = nullptr;  // this header
    void* surface_ = nullptr;
    bool adopted_ = false;
    GpuInfo info_;
};

}  // namespace cloth
