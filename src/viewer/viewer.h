// The interactive viewer (`clothsim view`): a GLFW window with a GL 4.3+ core context that the
// GPU solver computes in and the renderer draws from, and a Dear ImGui control panel.
#pragma once

#include <string>
#include <vector>

#include "backends/solver_factory.h"

namespace cloth::app {

struct ViewerOptions {
    std::string scenePath = "scenes/drape.json";
    std::vector<std::string> sets;  // --set KEY.PATH=JSON, applied through applyParameters()
    BackendChoice backend;          // an automatic one is settled once the window's context is made
    bool doubleAsked = false;       // --precision double: --backend auto picks the CPU
    int width = 1280, height = 800;
    bool vsync = true;
    // Multisampling: --samples N, or -1: 4 on a GPU, none on a software rasteriser
    // (viewer_main.cpp).
    int samples = -1;
    int frames = 0;  // > 0: run this many frames, then exit (tests, screenshots)
    // Written after the last frame: the one `frames` counts to, or the one in which the window
    // was closed (Ctrl+Q, the window manager).
    std::string screenshot;  // the window as PNG
    std::string outCsv;      // the solver's state, as run --out-csv writes it
};

// Runs the window until it is closed (or `frames` have been drawn). Throws GpuUnavailable when
// no window with a 4.3 context can be made, InputError for a bad scene.
int runViewer(const ViewerOptions& options);

}  // namespace cloth::app
