// app/window/ui.h: the window's Dear ImGui panel. The overlay owns ImGui's context and its GLFW and
// Vulkan backends (compiled from Debian's libimgui-dev sources, 1.86, which draw inside a render
// pass: one render pass and framebuffer over the render target's resolved image), and is a Pass
// that draws the panel last, over the scene. The panel shows the state, the help line, the counts
// (guides, strands drawn, segments, the OIT lists' or the compute raster's fragments and overflow),
// per-pass GPU times with a graph, and every setting of `wisp settings` as the control its type
// calls for (app/settings/settings_table.h's panelControl: sliders, checkboxes, lists, colours), section by
// section.
#pragma once

#include "app/settings/settings_table.h"
#include "gpu/handle.h"
#include "gpu/pass.h"

#include <deque>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

struct GLFWwindow;

namespace wisp {

namespace vk {
class Context;
struct ScopeTime;
} // namespace vk
class RenderTarget;

// What the panel shows, gathered by the window each frame.
struct PanelData {
    std::string status;                                 // Viewer::status()
    std::string help;                                   // viewerHelp()
    std::vector<std::string> counts;                    // one line each
    std::vector<std::pair<std::string, double>> passes; // GPU ms of the last completed frame
};

class UiOverlay : public Pass {
public:
    UiOverlay(const vk::Context& ctx, GLFWwindow* window, uint32_t framesInFlight);
    ~UiOverlay() override;
    UiOverlay(const UiOverlay&) = delete;
    UiOverlay& operator=(const UiOverlay&) = delete;

    // Draws into `target` (its resolved image); call again after the target is recreated (the
    // device idle).
    void setTarget(RenderTarget& target);
    // Builds this frame's panel over the settings as they are (`shown`). `apply(spec, value)`
    // applies an edited setting and returns "" or the error to show under it.
    using ApplySetting = std::function<std::string(const SettingSpec&, const SettingValue&)>;
    void build(const PanelData& data, const Settings& shown, const ApplySetting& apply, bool visible);
    bool wantsMouse() const;
    bool wantsKeyboard() const;

    const char* name() const override { return "ui"; }
    void declare(PassIo& io) override;
    void record(VkCommandBuffer cmd, FrameContext& frame) override;

private:
    const vk::Context& ctx_;
    RenderTarget* target_ = nullptr;
    vk::RenderPass renderPass_;
    vk::Framebuffer framebuffer_;
    vk::DescriptorPool pool_;
    std::deque<float> frameHistory_;            // GPU ms of recent frames, for the graph
    std::map<std::string, SettingValue> edits_; // a control being dragged: its value until released
    std::map<std::string, std::string> errors_; // the last error per setting
    bool drawn_ = false;                        // build() made draw data this frame
};

} // namespace wisp
