// The panel's parameter sliders come from scene/params.cpp's table: drawn headless (an ImGui
// context, no window), the panel draws a slider for exactly the table's viewer rows, and each
// row's value edited through its accessor reaches the session by the panel's path.
#include <gtest/gtest.h>
#include <imgui.h>

#include <cmath>

#include "scene/params.h"
#include "scene/scene_loader.h"
#include "viewer/viewer_session.h"
#include "viewer/viewer_ui.h"

namespace cloth {
namespace {

using app::ViewerParams;
using app::ViewerSession;
using app::ViewerUi;

// With wind, so every section's rows are drawn.
Scene windScene() {
    return loadScene(CLOTH_SOURCE_DIR "/scenes/hanging.json",
                     {"cloth.resolution=[8,6]", "integrator.substeps=5",
                      R"(wind={"direction": [1, 0, 0], "strength": 0.2})"});
}

// One frame of the panel without a window: what the sliders are is all that is looked at.
std::vector<std::string> drawnSliders(ViewerSession& session) {
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(1280, 2000);
    io.IniFilename = nullptr;
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
    ViewerUi ui;
    ImGui::NewFrame();
    app::drawPanel(session, ui);
    ImGui::Render();
    ImGui::DestroyContext();
    return ui.drawnParams;
}

// A material sheet with wind: the material's rows replace the per-vertex form's.
Scene materialScene() {
    return parseScene(R"({"cloth": {"resolution": [8, 6], "size": [1, 0.8]},
        "material": {"preset": "cotton"}, "pins": [[0, 0], [-1, 0]],
        "wind": {"direction": [1, 0, 0], "strength": 0.2},
        "integrator": {"method": "implicit_euler", "dt": 0.005, "substeps": 5}})",
                      "material (test)");
}

// The table's viewer rows the scene models (a row's accessor gives a value), section by section.
std::vector<std::string> tableSliders(const Scene& scene) {
    std::vector<std::string> rows;
    for (PanelSection section : {PanelSection::TimeStep, PanelSection::Forces, PanelSection::Wind})
        for (const ParamSpec& p : paramTable())
            if (p.slider.section == section && p.get(scene)) rows.emplace_back(p.path);
    return rows;
}

TEST(ViewerParamSliders, ThePanelDrawsASliderForEachViewerRowOfTheTable) {
    ViewerSession session(windScene(), {});
    EXPECT_EQ(drawnSliders(session), tableSliders(windScene()));
    ViewerSession material(materialScene(), {});
    EXPECT_EQ(drawnSliders(material), tableSliders(materialScene()));
}

TEST(ViewerParamSliders, ASceneWithoutWindHasNoWindSliders) {
    ViewerSession session(loadScene(CLOTH_SOURCE_DIR "/scenes/hanging.json"), {});
    for (const std::string& key : drawnSliders(session)) {
        EXPECT_NE(key, "wind.strength");
        EXPECT_NE(findParam(key), nullptr) << key;
    }
}

// Inside the slider's range, off the scene's value: the geometric middle of a log slider.
double sliderValue(const ParamSpec& p) {
    const SliderSpec& s = p.slider;
    double v = s.scale == SliderScale::Log && s.min > 0 ? std::sqrt(s.min * s.max)
                                                        : s.min + 0.37 * (s.max - s.min);
    return p.integer ? std::round(v) : v;
}

TEST(ViewerParamSliders, EachRowIsEditableThroughTheSession) {
    for (const Scene& scene : {windScene(), materialScene()}) {
        ViewerSession session(scene, {});
        for (const ParamSpec& p : paramTable()) {
            if (p.slider.section == PanelSection::Hidden || !p.get(scene)) continue;
            SCOPED_TRACE(p.path);
            ViewerParams edited = session.params();
            const double v = sliderValue(p);
            ASSERT_NE(*p.get(edited.scene), v);
            p.set(edited.scene, v);
            session.applyParameters(edited);
            ASSERT_TRUE(p.get(session.params().scene));
            EXPECT_EQ(*p.get(session.params().scene), v);
        }
    }
}

}  // namespace
}  // namespace cloth
