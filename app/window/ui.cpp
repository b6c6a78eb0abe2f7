// app/window/ui.cpp: the ImGui overlay: context, backends, the render pass over the resolved image, and
// the panel.
#include "app/window/ui.h"

#include "core/error.h"
#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/frame.h"
#include "renderer/render_target.h"

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <algorithm>
#include <array>
#include <cstdio>

namespace wisp {

namespace {

void checkImGuiVk(VkResult result)
{
    if (result != VK_SUCCESS)
        std::fprintf(stderr, "wisp: ImGui's Vulkan backend: %s\n", vk::resultName(result));
}

constexpr size_t kHistory = 240; // frames in the GPU-time graph

} // namespace

UiOverlay::UiOverlay(const vk::Context& ctx, GLFWwindow* window, uint32_t framesInFlight) : ctx_(ctx)
{
    std::array<VkDescriptorPoolSize, 1> sizes = {{{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16}}};
    VkDescriptorPoolCreateInfo poolInfo{.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
                                        .flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT,
                                        .maxSets = 16,
                                        .poolSizeCount = uint32_t(sizes.size()),
                                        .pPoolSizes = sizes.data()};
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VK_CHECK(vkCreateDescriptorPool(ctx.device(), &poolInfo, nullptr, &pool));
    ctx.setName(pool, VK_OBJECT_TYPE_DESCRIPTOR_POOL, "ui.pool");
    pool_ = vk::DescriptorPool(ctx.device(), pool);

    // One pass over the resolved image, which the frame has in COLOR_ATTACHMENT_OPTIMAL already
    // (the pass declares it): no layout change, the drawn scene loaded.
    VkAttachmentDescription attachment{.format = RenderTarget::kColorFormat,
                                       .samples = VK_SAMPLE_COUNT_1_BIT,
                                       .loadOp = VK_ATTACHMENT_LOAD_OP_LOAD,
                                       .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
                                       .stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
                                       .stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
                                       .initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                       .finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{
        .pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS, .colorAttachmentCount = 1, .pColorAttachments = &ref};
    VkSubpassDependency dependency{.srcSubpass = VK_SUBPASS_EXTERNAL,
                                   .dstSubpass = 0,
                                   .srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                                   .dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                                   .srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                                   .dstAccessMask =
                                       VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT};
    VkRenderPassCreateInfo rpInfo{.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO,
                                  .attachmentCount = 1,
                                  .pAttachments = &attachment,
                                  .subpassCount = 1,
                                  .pSubpasses = &subpass,
                                  .dependencyCount = 1,
                                  .pDependencies = &dependency};
    VkRenderPass renderPass = VK_NULL_HANDLE;
    VK_CHECK(vkCreateRenderPass(ctx.device(), &rpInfo, nullptr, &renderPass));
    ctx.setName(renderPass, VK_OBJECT_TYPE_RENDER_PASS, "ui.renderpass");
    renderPass_ = vk::RenderPass(ctx.device(), renderPass);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr; // nothing written beside the user's files
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForVulkan(window, true); // chains the window's own callbacks
    ImGui_ImplVulkan_InitInfo info{.Instance = ctx.instance(),
                                   .PhysicalDevice = ctx.physicalDevice(),
                                   .Device = ctx.device(),
                                   .QueueFamily = ctx.queueFamily(),
                                   .Queue = ctx.queue(),
                                   .PipelineCache = VK_NULL_HANDLE,
                                   .DescriptorPool = pool_,
                                   .Subpass = 0,
                                   .MinImageCount = std::max(framesInFlight, 2u),
                                   .ImageCount = std::max(framesInFlight, 2u),
                                   .MSAASamples = VK_SAMPLE_COUNT_1_BIT,
                                   .Allocator = nullptr,
                                   .CheckVkResultFn = checkImGuiVk};
    if (!ImGui_ImplVulkan_Init(&info, renderPass_))
        throw UserError("the ImGui panel could not initialise its Vulkan backend");
    ctx.submitAndWait([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
    ImGui_ImplVulkan_DestroyFontUploadObjects();
}

UiOverlay::~UiOverlay()
{
    vkDeviceWaitIdle(ctx_.device()); // unchecked: after a lost device it fails at once, and destructors do not throw
    ImGui_ImplVulkan_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

void UiOverlay::setTarget(RenderTarget& target)
{
    target_ = &target;
    VkImageView view = target.resultImage().view();
    VkExtent2D e = target.extent();
    VkFramebufferCreateInfo info{.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO,
                                 .renderPass = renderPass_,
                                 .attachmentCount = 1,
                                 .pAttachments = &view,
                                 .width = e.width,
                                 .height = e.height,
                                 .layers = 1};
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    VK_CHECK(vkCreateFramebuffer(ctx_.device(), &info, nullptr, &framebuffer));
    ctx_.setName(framebuffer, VK_OBJECT_TYPE_FRAMEBUFFER, "ui.framebuffer");
    framebuffer_ = vk::Framebuffer(ctx_.device(), framebuffer);
}

bool UiOverlay::wantsMouse() const
{
    return ImGui::GetIO().WantCaptureMouse;
}

bool UiOverlay::wantsKeyboard() const
{
    return ImGui::GetIO().WantCaptureKeyboard;
}

namespace {

// One setting's control. Returns true with `value` changed when the edit is to be applied now:
// live settings while a slider moves, the others (which rebuild the renderer or the solver) when
// it is let go.
bool settingControl(const SettingSpec& spec, SettingValue& value, std::map<std::string, SettingValue>& edits)
{
    PanelControl c = panelControl(spec);
    const char* label = spec.name.c_str();
    bool changed = false;
    bool held = edits.count(spec.name) > 0;
    if (held)
        value = edits[spec.name];
    ImGui::BeginDisabled(!c.enabled);
    if (spec.optional()) { // a box for "its own default" beside the value's control
        bool own = !value.unset;
        ImGui::PushID(label);
        if (ImGui::Checkbox("##set", &own)) {
            value.unset = !own;
            changed = true;
        }
        ImGui::PopID();
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("off: %s", spec.unsetText.c_str());
        ImGui::SameLine();
    }
    ImGui::BeginDisabled(value.unset);
    ImGui::SetNextItemWidth(spec.type == SettingType::Vector || spec.type == SettingType::Color ? 200.0f : 150.0f);
    ImGuiSliderFlags flags = (c.logarithmic ? ImGuiSliderFlags_Logarithmic : 0) | ImGuiSliderFlags_AlwaysClamp;
    switch (c.kind) {
    case PanelControl::Kind::Slider: {
        float v = float(value.number);
        if (ImGui::SliderFloat(label, &v, float(c.min), float(c.max), "%.4g", flags)) {
            value.number = double(v);
            changed = true;
        }
        break;
    }
    case PanelControl::Kind::IntegerSlider: {
        // ImGui's sliders take ints: ranges past them (the seed) are clamped to what an int holds.
        int lo = int(std::max(c.min, -2147483647.0)), hi = int(std::min(c.max, 2147483647.0));
        int v = int(std::clamp(value.number, double(lo), double(hi)));
        if (ImGui::SliderInt(label, &v, lo, hi, "%d", flags)) {
            value.number = double(v);
            changed = true;
        }
        break;
    }
    case PanelControl::Kind::Checkbox: {
        bool v = value.number != 0.0;
        if (ImGui::Checkbox(label, &v)) {
            value.number = v ? 1.0 : 0.0;
            changed = true;
        }
        break;
    }
    case PanelControl::Kind::Combo: {
        int v = int(value.number);
        std::string items;
        for (const std::string& choice : spec.choices)
            items += choice + '\0';
        if (ImGui::Combo(label, &v, items.c_str())) {
            value.number = double(v);
            changed = true;
        }
        break;
    }
    case PanelControl::Kind::Color:
    case PanelControl::Kind::Vector: {
        float v[3] = {float(value.vector.x), float(value.vector.y), float(value.vector.z)};
        bool edited = c.kind == PanelControl::Kind::Color
                          ? ImGui::ColorEdit3(label, v, ImGuiColorEditFlags_Float)
                          : ImGui::SliderFloat3(label, v, float(c.min), float(c.max), "%.3g", flags);
        if (edited) {
            value.vector = glm::dvec3(v[0], v[1], v[2]);
            changed = true;
        }
        break;
    }
    }
    bool active = ImGui::IsItemActive();
    ImGui::EndDisabled();
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
        std::string when = !c.enabled ? "needs a restart: --set " + spec.name + "=..."
                           : spec.change == SettingChange::Live
                               ? std::string("applies at once")
                               : "applies when let go: rebuilds the " + std::string(changeName(spec.change));
        ImGui::SetTooltip("%s\n%s\n%s", spec.help.c_str(), spec.allowed().c_str(), when.c_str());
    }
    if (spec.change == SettingChange::Live)
        return changed;
    // Settings that rebuild something wait for the control to be let go.
    if (active) {
        if (changed)
            edits[spec.name] = value;
        return false;
    }
    if (held) {
        edits.erase(spec.name);
        return true;
    }
    return changed; // a click: a checkbox, a list
}

} // namespace

void UiOverlay::build(const PanelData& data, const Settings& shown, const ApplySetting& apply, bool visible)
{
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    double total = 0.0;
    for (const auto& [name, ms] : data.passes)
        total += ms;
    frameHistory_.push_back(float(total));
    while (frameHistory_.size() > kHistory)
        frameHistory_.pop_front();
    if (visible) {
        ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowSize(ImVec2(400, 520), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowBgAlpha(0.8f);
        ImGui::Begin("Wisp (H hides)");
        ImGui::TextWrapped("%s", data.status.c_str());
        if (ImGui::CollapsingHeader("Keys", ImGuiTreeNodeFlags_DefaultOpen))
            ImGui::TextWrapped("%s", data.help.c_str());
        if (ImGui::CollapsingHeader("Counts", ImGuiTreeNodeFlags_DefaultOpen))
            for (const std::string& line : data.counts)
                ImGui::TextWrapped("%s", line.c_str());
        if (ImGui::CollapsingHeader("GPU time per pass", ImGuiTreeNodeFlags_DefaultOpen)) {
            std::vector<float> history(frameHistory_.begin(), frameHistory_.end());
            float top = history.empty() ? 1.0f : *std::max_element(history.begin(), history.end());
            char label[64];
            std::snprintf(label, sizeof(label), "frame %.2f ms", total);
            ImGui::PlotLines("##frame", history.data(), int(history.size()), 0, label, 0.0f, top * 1.2f,
                             ImVec2(-1, 60));
            for (const auto& [name, ms] : data.passes) {
                ImGui::Text("%-14s %7.3f ms", name.c_str(), ms);
                ImGui::SameLine(200);
                ImGui::ProgressBar(total > 0.0 ? float(ms / total) : 0.0f, ImVec2(-1, 0), "");
            }
        }
        // Every setting, section by section (the table's groups, in its order).
        std::string section;
        bool open = false;
        for (const SettingSpec& spec : settingSpecs()) {
            if (section != groupName(spec.group)) {
                section = groupName(spec.group);
                std::string title = "Settings: " + section;
                open = ImGui::CollapsingHeader(title.c_str());
            }
            if (!open)
                continue;
            SettingValue value = spec.get(shown);
            if (settingControl(spec, value, edits_))
                errors_[spec.name] = apply(spec, value);
            if (auto e = errors_.find(spec.name); e != errors_.end() && !e->second.empty())
                ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", e->second.c_str());
        }
        ImGui::End();
    }
    ImGui::Render();
    drawn_ = true;
}

void UiOverlay::declare(PassIo& io)
{
    io.use(target_->result(), Access::ColorAttachment);
}

void UiOverlay::record(VkCommandBuffer cmd, FrameContext&)
{
    if (!drawn_)
        return;
    drawn_ = false;
    VkExtent2D e = target_->extent();
    VkRenderPassBeginInfo begin{.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO,
                                .renderPass = renderPass_,
                                .framebuffer = framebuffer_,
                                .renderArea = {{0, 0}, e}};
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
    vkCmdEndRenderPass(cmd);
}

} // namespace wisp
