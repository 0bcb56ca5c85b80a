// The panel's parameter sliders come from scene/params.cpp's table: drawn headless (an ImGui
// context, no window), the panel draws a slider for exactly the table's viewer rows, and each
// row's value edited through its accessor reaches the session by the panel's path.
#include <gtest/gtest.h>
#include <imgui.h>

#include <cmath>

#include "model/stability.h"
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

// The panel's frame-step button keeps the displayed frame (substeps × dt) and fits the step to the
// method: after switching the drape (symplectic Euler, 42 steps of 0.4 ms) to vbd or implicit
// Euler, one step a frame; after switching a 1/60 s vbd drape to symplectic Euler, the fewest
// equal steps at most 0.9 of the bound; nothing where the step fits already.
TEST(ViewerFrameStep, KeepsTheFrameAndFitsTheStepToTheMethod) {
    Scene drape = loadScene(CLOTH_SOURCE_DIR "/scenes/drape.json");
    const double frame = drape.integrator.substeps * drape.integrator.dt;
    EXPECT_FALSE(app::frameStep(drape.integrator, stableDt(drape)));  // inside its bound already
    for (Method m : {Method::Vbd, Method::ImplicitEuler}) {
        drape.integrator.method = m;
        const auto fit = app::frameStep(drape.integrator, stableDt(drape));
        ASSERT_TRUE(fit) << methodName(m);
        EXPECT_EQ(fit->substeps, 1);
        EXPECT_DOUBLE_EQ(fit->dt, frame);
        IntegratorSpec once = drape.integrator;
        once.dt = fit->dt, once.substeps = 1;
        EXPECT_FALSE(app::frameStep(once, stableDt(drape))) << methodName(m);
    }
    drape.integrator.method = Method::SymplecticEuler;
    drape.integrator.dt = 1.0 / 60, drape.integrator.substeps = 1;
    const double bound = stableDt(drape);
    const auto fit = app::frameStep(drape.integrator, bound);
    ASSERT_TRUE(fit);
    EXPECT_LE(fit->dt, 0.9 * bound);
    EXPECT_GT(fit->dt * fit->substeps, 0.9 * bound * (fit->substeps - 1));  // the fewest
    EXPECT_NEAR(fit->dt * fit->substeps, 1.0 / 60, 1e-15);
    drape.integrator.method = Method::ExplicitEuler;  // without damping: no stable step to offer
    drape.material->airDamping = 0;
    EXPECT_FALSE(app::frameStep(drape.integrator, stableDt(drape)));
}

}  // namespace
}  // namespace cloth
