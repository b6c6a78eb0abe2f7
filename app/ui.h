// app/ui.h: the window's Dear ImGui panel. The overlay owns ImGui's context and its GLFW and
// Vulkan backends (compiled from Debian's libimgui-dev sources, 1.86, which draw inside a render
// pass: one render pass and framebuffer over the render target's resolved image), and is a Pass
// that draws the panel last, over the scene. The panel shows the state, the help line, the counts
// (guides, strands drawn, segments, OIT fragments and overflow), per-pass GPU times with a graph,
// and edits every setting of `wisp settings` live through the same registry as --set.
#pragma once

#include "gpu/pass.h"
#include "gpu/handle.h"

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
}
class RenderTarget;

// What the panel shows, gathered by the window each frame.
struct PanelData {
    std::string status;                      // Viewer::status()
    std::string help;                        // viewerHelp()
    std::vector<std::string> counts;         // one line each
    std::vector<std::pair<std::string, double>> passes;  // GPU ms of the last completed frame
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
    // Builds this frame's panel. `apply(name, value)` applies a setting and returns "" or the
    // error to show under it; `value(name)` gives a setting's current value as text.
    void build(const PanelData& data, const std::function<std::string(const std::string&, const std::string&)>& apply,
               const std::function<std::string(const std::string&)>& value, bool visible);
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
    std::deque<float> frameHistory_;  // GPU ms of recent frames, for the graph
    std::map<std::string, std::string> edits_;   // the text being edited per setting
    std::map<std::string, std::string> errors_;  // the last error per setting
    std::set<std::string> editing_;              // settings whose field has the keyboard
    bool drawn_ = false;                         // build() made draw data this frame
};

}  // namespace wisp
