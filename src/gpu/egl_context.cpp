#include "gpu/egl_context.h"

#include <GL/glew.h>
// GLEW first: it must precede every other GL header.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include "gpu/gpu_options.h"
#include "model/errors.h"

namespace cloth {
namespace {

// DESIGN.md §3 needs compute shaders and SSBOs: OpenGL 4.3. 4.5 is asked for first.
constexpr int kMinorVersions[] = {5, 4, 3};

bool hasExtension(const char* list, const char* name) {
    if (list == nullptr) return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = std::strstr(list, name); p != nullptr; p = std::strstr(p + n, name)) {
        const bool startOk = p == list || p[-1] == ' ';
        if (startOk && (p[n] == ' ' || p[n] == '\0')) return true;
    }
    return false;
}

std::string eglErrorName(EGLint e) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "EGL error 0x%04x", unsigned(e));
    return buf;
}

template <typename F>
F eglProc(const char* name) {
    return reinterpret_cast<F>(eglGetProcAddress(name));
}

// A display with a GL 4.3+ core context current on it, or an error saying why not.
struct Attempt {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    EGLSurface surface = EGL_NO_SURFACE;
    std::string error;
};

EGLConfig chooseConfig(EGLDisplay display, bool needSurface) {
    const char* ext = eglQueryString(display, EGL_EXTENSIONS);
    if (!needSurface && hasExtension(ext, "EGL_KHR_no_config_context")) return EGL_NO_CONFIG_KHR;
    const EGLint attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                              EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display, attribs, &config, 1, &count) || count == 0) return nullptr;
    return config;
}

EGLContext createCoreContext(EGLDisplay display, EGLConfig config) {
    for (const int minor : kMinorVersions) {
        for (const bool debug : {true, false}) {
#ifdef NDEBUG
            if (debug) continue;  // the KHR_debug context is for debug builds only
#endif
            std::vector<EGLint> a = {
                EGL_CONTEXT_MAJOR_VERSION,       4,
                EGL_CONTEXT_MINOR_VERSION,       minor,
                EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT};
            if (debug) a.insert(a.end(), {EGL_CONTEXT_OPENGL_DEBUG, EGL_TRUE});
            a.push_back(EGL_NONE);
            EGLContext c = eglCreateContext(display, config, EGL_NO_CONTEXT, a.data());
            if (c != EGL_NO_CONTEXT) return c;
        }
    }
    return EGL_NO_CONTEXT;
}

// Initialises `display` and makes a core context current on it (surfaceless where the display
// allows, else on a 1×1 pbuffer). On failure the display is terminated again.
Attempt tryDisplay(EGLDisplay display) {
    Attempt a;
    if (display == EGL_NO_DISPLAY) return {.error = "no display"};
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor))
        return {.error = "eglInitialize: " + eglErrorName(eglGetError())};
    a.display = display;
    const bool surfaceless =
        hasExtension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context");
    if (!eglBindAPI(EGL_OPENGL_API)) a.error = "eglBindAPI(OpenGL): " + eglErrorName(eglGetError());
    EGLConfig config = a.error.empty() ? chooseConfig(display, !surfaceless) : nullptr;
    if (a.error.empty() && config == nullptr && !surfaceless) a.error = "no pbuffer config";
    if (a.error.empty()) {
        a.context = createCoreContext(display, config);
        if (a.context == EGL_NO_CONTEXT) a.error = "no OpenGL 4.3+ core context";
    }
    if (a.error.empty() && !surfaceless) {
        const EGLint pb[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
        a.surface = eglCreatePbufferSurface(display, config, pb);
        if (a.surface == EGL_NO_SURFACE) a.error = "pbuffer: " + eglErrorName(eglGetError());
    }
    if (a.error.empty() && !eglMakeCurrent(display, a.surface, a.surface, a.context))
        a.error = "eglMakeCurrent: " + eglErrorName(eglGetError());
    if (!a.error.empty()) {
        if (a.context != EGL_NO_CONTEXT) eglDestroyContext(display, a.context);
        if (a.surface != EGL_NO_SURFACE) eglDestroySurface(display, a.surface);
        eglTerminate(display);
        a.display = EGL_NO_DISPLAY;
    }
    return a;
}

struct Device {
    EGLDeviceEXT handle;
    int index;
    bool software;
};

// "0 (software)": the index EGL and CLOTH_EGL_DEVICE give it, and its kind.
std::string deviceLabel(const Device& d) {
    return std::to_string(d.index) + (d.software ? " (software)" : " (hardware)");
}

// Every EGL device in index order; Mesa marks its software rasterisers with
// EGL_MESA_device_software.
std::vector<Device> queryDevices() {
    auto queryDevices = eglProc<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
    auto queryString = eglProc<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
    EGLint n = 0;
    if (queryDevices == nullptr || !queryDevices(0, nullptr, &n) || n <= 0) return {};
    std::vector<EGLDeviceEXT> handles(n);
    queryDevices(n, handles.data(), &n);
    std::vector<Device> devices;
    for (int i = 0; i < n; ++i) {
        const char* ext = queryString ? queryString(handles[i], EGL_EXTENSIONS) : nullptr;
        devices.push_back({handles[i], i, hasExtension(ext, "EGL_MESA_device_software")});
    }
    return devices;
}

// The devices in the order to try: the configured one alone (gpuSetup), else hardware first.
std::vector<Device> devicesToTry(std::vector<Device> devices) {
    if (const int want = gpuSetup().eglDevice; want >= 0) {
        if (want >= int(devices.size()))
            throw InputError("", "CLOTH_EGL_DEVICE",
                             std::to_string(want) + " is not a device index in [0, " +
                                 std::to_string(int(devices.size()) - 1) + "]");
        return {devices[size_t(want)]};
    }
    std::stable_partition(devices.begin(), devices.end(),
                          [](const Device& d) { return !d.software; });
    return devices;
}

#ifndef NDEBUG
void GLAPIENTRY debugCallback(GLenum source, GLenum type, GLuint, GLenum severity, GLsizei,
                              const GLchar* message, const void*) {
    // Compiler logs reach the user through the shader loader, with file names mapped back.
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION || source == GL_DEBUG_SOURCE_SHADER_COMPILER)
        return;
    std::fprintf(stderr, "GL debug (%s): %s\n", type == GL_DEBUG_TYPE_ERROR ? "error" : "note",
                 message);
}
#endif

std::string glString(GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? reinterpret_cast<const char*>(s) : "";
}

}  // namespace

GlContext& GlContext::instance() {
    // Made once and never destroyed: solvers may outlive any static that would own it, and the
    // driver frees everything at exit.
    static GlContext* context = new GlContext();
    return *context;
}

GlContext::GlContext() {
    // A context current on this thread already (e.g. the viewer's window) is used as it is.
    adopted_ = glGetString(GL_VERSION) != nullptr;
    if (adopted_)
        info_.platform = "adopted the caller's current context";
    else
        createEgl();
    loadFunctions();
    queryInfo();
}

void GlContext::createEgl() {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto platformDisplay = eglProc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
    std::string errors;
    auto take = [&](const Attempt& a, const std::string& platform) {
        if (a.error.empty()) {
            display_ = a.display;
            context_ = a.context;
            surface_ = a.surface;
            info_.platform = platform;
            return true;
        }
        errors += "\n  " + platform + ": " + a.error;
        return false;
    };
    if (platformDisplay != nullptr && hasExtension(client, "EGL_EXT_platform_device")) {
        const std::vector<Device> devices = queryDevices();
        for (const Device& d : devices)
            info_.eglDevices += (info_.eglDevices.empty() ? "" : ", ") + deviceLabel(d);
        for (const Device& d : devicesToTry(devices)) {
            const Attempt a =
                tryDisplay(platformDisplay(EGL_PLATFORM_DEVICE_EXT, d.handle, nullptr));
            if (take(a, "EGL device " + deviceLabel(d))) return;
        }
    }
    if (platformDisplay != nullptr && hasExtension(client, "EGL_MESA_platform_surfaceless")) {
        const Attempt a = tryDisplay(
            platformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
        if (take(a, "EGL surfaceless (Mesa)")) return;
    }
    if (take(tryDisplay(eglGetDisplay(EGL_DEFAULT_DISPLAY)), "EGL default display")) return;
    throw GpuUnavailable("no headless OpenGL 4.3+ context could be made:" + errors);
}

void GlContext::loadFunctions() {
    // GLEW looks for a GLX display and reports GLEW_ERROR_NO_GLX_DISPLAY on an EGL context, yet
    // loads every entry point; what matters is that the compute entry points exist.
    glewExperimental = GL_TRUE;
    const GLenum status = glewInit();
    while (glGetError() != GL_NO_ERROR) {  // glewInit's probing leaves errors behind
    }
    if (glDispatchCompute == nullptr || glGetIntegeri_v == nullptr) {
        throw GpuUnavailable(std::string("OpenGL compute entry points missing (glewInit: ") +
                             reinterpret_cast<const char*>(glewGetErrorString(status)) + ")");
    }
#ifndef NDEBUG
    if (glDebugMessageCallback != nullptr) {
        glEnable(GL_DEBUG_OUTPUT);
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback(debugCallback, nullptr);
    }
#endif
}

void GlContext::queryInfo() {
    GpuInfo& g = info_;
    if (!adopted_) {
        g.eglVendor = eglQueryString(display_, EGL_VENDOR);
        g.eglVersion = eglQueryString(display_, EGL_VERSION);
    }
    g.renderer = glString(GL_RENDERER);
    g.vendor = glString(GL_VENDOR);
    g.version = glString(GL_VERSION);
    g.glslVersion = glString(GL_SHADING_LANGUAGE_VERSION);
    glGetIntegerv(GL_MAJOR_VERSION, &g.glMajor);
    glGetIntegerv(GL_MINOR_VERSION, &g.glMinor);
    if (g.glMajor * 10 + g.glMinor < 43)
        throw GpuUnavailable("OpenGL " + g.version + " on " + g.renderer +
                             ": compute shaders need 4.3 or later");
    for (GLuint d = 0; d < 3; ++d) {
        glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, d, &g.maxWorkGroupCount[d]);
        glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_SIZE, d, &g.maxWorkGroupSize[d]);
    }
    glGetIntegerv(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS, &g.maxInvocations);
    glGetIntegerv(GL_MAX_COMPUTE_SHARED_MEMORY_SIZE, &g.maxSharedMemory);
    GLint64 block = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block);
    g.maxStorageBlockSize = block;
    glGetInteger64v(GL_MAX_UNIFORM_BLOCK_SIZE, &block);
    g.maxUniformBlockSize = block;
    glGetIntegerv(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS, &g.maxComputeStorageBlocks);
    GLint bits = 0;
    glGetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &bits);
    g.timerQueries = bits > 0;
    g.software = softwareRenderer(g.renderer);
}

bool softwareRenderer(const std::string& renderer) {
    for (const char* sw : {"llvmpipe", "softpipe", "swrast", "SwiftShader"})
        if (renderer.find(sw) != std::string::npos) return true;
    return false;
}

void GlContext::makeCurrent() const {
    if (adopted_ || eglGetCurrentContext() == context_) return;
    if (eglMakeCurrent(display_, surface_, surface_, context_)) return;
    const EGLint error = eglGetError();
    // EGL binds a context to one thread at a time: a GPU solver stays on the thread that made it.
    if (error == EGL_BAD_ACCESS)
        throw std::runtime_error(
            "the GPU solver was called from a thread other than the one that made it (its EGL "
            "context is current there, and EGL binds a context to one thread): call it from that "
            "thread");
    throw GpuUnavailable("eglMakeCurrent failed: " + eglErrorName(error));
}

std::string GpuInfo::describe() const {
    char buf[1024];
    std::snprintf(buf, sizeof buf,
                  "platform:          %s\n"
                  "EGL devices:       %s\n"
                  "EGL:               %s %s\n"
                  "GL renderer:       %s (%s)%s\n"
                  "GL version:        %s, GLSL %s\n"
                  "work-group count:  %d x %d x %d\n"
                  "work-group size:   %d x %d x %d, at most %d invocations\n"
                  "shared memory:     %d bytes per work group\n"
                  "SSBO block size:   %lld bytes\n"
                  "uniform block:     %lld bytes\n"
                  "storage blocks:    %d per compute shader\n"
                  "timer queries:     %s\n",
                  platform.c_str(), eglDevices.empty() ? "-" : eglDevices.c_str(),
                  eglVendor.empty() ? "-" : eglVendor.c_str(), eglVersion.c_str(), renderer.c_str(),
                  vendor.c_str(), software ? " [software]" : "", version.c_str(),
                  glslVersion.c_str(), maxWorkGroupCount[0], maxWorkGroupCount[1],
                  maxWorkGroupCount[2], maxWorkGroupSize[0], maxWorkGroupSize[1],
                  maxWorkGroupSize[2], maxInvocations, maxSharedMemory, maxStorageBlockSize,
                  maxUniformBlockSize, maxComputeStorageBlocks, timerQueries ? "yes" : "no");
    return buf;
}

}  // namespace cloth
