// app/window.cpp: GLFW window, Vulkan surface and swapchain (recreated on resize, idle while
// minimized), input to the orbit camera, and the per-frame blit from the render target.
#include "app/window.h"

#include "app/image_io.h"
#include "app/settings_registry.h"
#include "app/ui.h"
#include "app/viewer.h"
#include "core/error.h"
#include "physics/gpu_solver.h"
#include "assets/head.h"
#include "gpu/frame.h"
#include "renderer/renderer.h"
#include "gpu/check.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <set>
#include <cstdio>
#include <cstdlib>

namespace wisp {

namespace {

// Copies the render target's result into the acquired swapchain image.
class PresentBlitPass : public Pass {
public:
    PresentBlitPass(RenderTarget& target) : target_(target) {}
    const char* name() const override { return "present"; }
    void setSwapchainImage(TrackedImage& image, VkExtent2D extent)
    {
        swapImage_ = &image;
        swapExtent_ = extent;
    }
    void declare(PassIo& io) override
    {
        io.use(target_.result(), Access::TransferSrc);
        io.use(*swapImage_, Access::TransferDst);
    }
    void record(VkCommandBuffer cmd, FrameContext&) override
    {
        VkExtent2D src = target_.extent();
        VkImageBlit2 region{.sType = VK_STRUCTURE_TYPE_IMAGE_BLIT_2,
                            .srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                            .srcOffsets = {{0, 0, 0}, {int32_t(src.width), int32_t(src.height), 1}},
                            .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                            .dstOffsets = {{0, 0, 0}, {int32_t(swapExtent_.width), int32_t(swapExtent_.height), 1}}};
        VkBlitImageInfo2 info{.sType = VK_STRUCTURE_TYPE_BLIT_IMAGE_INFO_2,
                              .srcImage = target_.resultImage().get(),
                              .srcImageLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                              .dstImage = swapImage_->image,
                              .dstImageLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                              .regionCount = 1,
                              .pRegions = &region,
                              .filter = VK_FILTER_NEAREST};
        vkCmdBlitImage2(cmd, &info);
    }

private:
    RenderTarget& target_;
    TrackedImage* swapImage_ = nullptr;
    VkExtent2D swapExtent_{};
};

struct Swapchain {
    VkDevice device = VK_NULL_HANDLE;
    VkSwapchainKHR handle = VK_NULL_HANDLE;
    VkExtent2D extent{};
    std::vector<TrackedImage> images;
    std::vector<vk::Semaphore> renderDone;  // one per image: signalled by the frame, waited by present

    ~Swapchain() { destroy(); }
    void destroy()
    {
        renderDone.clear();
        images.clear();
        if (handle)
            vkDestroySwapchainKHR(device, std::exchange(handle, VK_NULL_HANDLE), nullptr);
    }
};

void createSwapchain(const vk::Context& ctx, VkSurfaceKHR surface, VkExtent2D wanted, Swapchain& sc)
{
    VkSurfaceCapabilitiesKHR caps;
    VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(ctx.physicalDevice(), surface, &caps));
    uint32_t formatCount = 0;
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physicalDevice(), surface, &formatCount, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(formatCount);
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physicalDevice(), surface, &formatCount, formats.data()));
    VkSurfaceFormatKHR format = formats.front();
    for (const VkSurfaceFormatKHR& f : formats)
        if ((f.format == VK_FORMAT_B8G8R8A8_SRGB || f.format == VK_FORMAT_R8G8B8A8_SRGB) &&
            f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR)
            format = f;
    VkExtent2D extent = caps.currentExtent.width != UINT32_MAX
                            ? caps.currentExtent
                            : VkExtent2D{std::clamp(wanted.width, caps.minImageExtent.width, caps.maxImageExtent.width),
                                         std::clamp(wanted.height, caps.minImageExtent.height, caps.maxImageExtent.height)};
    uint32_t imageCount = caps.minImageCount + 1;
    if (caps.maxImageCount > 0)
        imageCount = std::min(imageCount, caps.maxImageCount);
    if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
        throw UserError("the window surface does not accept transfers (VK_IMAGE_USAGE_TRANSFER_DST_BIT)");

    VkSwapchainKHR old = sc.handle;
    VkSwapchainCreateInfoKHR info{.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR,
                                  .surface = surface,
                                  .minImageCount = imageCount,
                                  .imageFormat = format.format,
                                  .imageColorSpace = format.colorSpace,
                                  .imageExtent = extent,
                                  .imageArrayLayers = 1,
                                  .imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT,
                                  .imageSharingMode = VK_SHARING_MODE_EXCLUSIVE,
                                  .preTransform = caps.currentTransform,
                                  .compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR,
                                  .presentMode = VK_PRESENT_MODE_FIFO_KHR,
                                  .clipped = VK_TRUE,
                                  .oldSwapchain = old};
    VkSwapchainKHR handle = VK_NULL_HANDLE;
    VK_CHECK(vkCreateSwapchainKHR(ctx.device(), &info, nullptr, &handle));
    sc.handle = VK_NULL_HANDLE;  // keep `old` alive until the new one exists
    sc.destroy();
    if (old)
        vkDestroySwapchainKHR(ctx.device(), old, nullptr);
    sc.device = ctx.device();
    sc.handle = handle;
    sc.extent = extent;
    ctx.setName(handle, VK_OBJECT_TYPE_SWAPCHAIN_KHR, "window.swapchain");

    uint32_t count = 0;
    VK_CHECK(vkGetSwapchainImagesKHR(ctx.device(), handle, &count, nullptr));
    std::vector<VkImage> images(count);
    VK_CHECK(vkGetSwapchainImagesKHR(ctx.device(), handle, &count, images.data()));
    for (VkImage image : images) {
        sc.images.push_back({.image = image});
        sc.renderDone.push_back(ctx.createSemaphore("window.renderDone"));
    }
}

struct Input {
    Viewer* viewer = nullptr;
    UiOverlay* ui = nullptr;
    double lastX = 0.0, lastY = 0.0;
    bool orbiting = false, panning = false, dragging = false;
};

// GLFW keys to the viewer's (the one table of what each key does is app/viewer.cpp).
bool viewerKeyOf(int glfwKey, ViewerKey& key)
{
    switch (glfwKey) {
    case GLFW_KEY_LEFT: key = ViewerKey::SphereLeft; return true;
    case GLFW_KEY_RIGHT: key = ViewerKey::SphereRight; return true;
    case GLFW_KEY_UP: key = ViewerKey::SphereUp; return true;
    case GLFW_KEY_DOWN: key = ViewerKey::SphereDown; return true;
    case GLFW_KEY_PAGE_UP: key = ViewerKey::SphereNear; return true;
    case GLFW_KEY_PAGE_DOWN: key = ViewerKey::SphereFar; return true;
    case GLFW_KEY_J: key = ViewerKey::LightLeft; return true;
    case GLFW_KEY_L: key = ViewerKey::LightRight; return true;
    case GLFW_KEY_I: key = ViewerKey::LightUp; return true;
    case GLFW_KEY_K: key = ViewerKey::LightDown; return true;
    case GLFW_KEY_A: key = ViewerKey::HeadLeft; return true;
    case GLFW_KEY_D: key = ViewerKey::HeadRight; return true;
    case GLFW_KEY_W: key = ViewerKey::Wind; return true;
    case GLFW_KEY_EQUAL: case GLFW_KEY_KP_ADD: key = ViewerKey::WindStronger; return true;
    case GLFW_KEY_MINUS: case GLFW_KEY_KP_SUBTRACT: key = ViewerKey::WindWeaker; return true;
    case GLFW_KEY_SPACE: key = ViewerKey::Pause; return true;
    case GLFW_KEY_N: key = ViewerKey::Step; return true;
    case GLFW_KEY_R: key = ViewerKey::Reset; return true;
    case GLFW_KEY_P: key = ViewerKey::Screenshot; return true;
    case GLFW_KEY_F5: key = ViewerKey::Reload; return true;
    case GLFW_KEY_O: key = ViewerKey::SphereToggle; return true;
    case GLFW_KEY_H: key = ViewerKey::Help; return true;
    case GLFW_KEY_ESCAPE: key = ViewerKey::Quit; return true;
    case GLFW_KEY_T: key = ViewerKey::Play; return true;
    case GLFW_KEY_F2: key = ViewerKey::SaveScene; return true;
    case GLFW_KEY_F3: key = ViewerKey::LoadScene; return true;
    default: return false;
    }
}

// Rebuilds the shaders' SPIR-V in the build tree (hot reload): the build's own shader target,
// through cmake, so an edited include rebuilds every stage that uses it. False (with the build's
// output on stderr) when there is no build tree or the build fails.
bool rebuildShaders()
{
    std::string command = "cmake --build '" WISP_BINARY_DIR "' --target wisp_shaders >&2";
    std::fprintf(stderr, "wisp: reloading shaders: %s\n", command.c_str());
    return std::system(command.c_str()) == 0;
}

}  // namespace

void requireDisplay()
{
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((!display || !*display) && (!wayland || !*wayland))
        throw UserError("no display (DISPLAY and WAYLAND_DISPLAY are unset): 'wisp view' needs a window; "
                        "render offscreen with 'wisp render --out FILE.png' instead");
}

int runWindow(const WindowOptions& options)
{
    requireDisplay();
    if (!options.screenshot.empty())
        checkPngOutput(options.screenshot);
    const Head& head = options.scene->head;

    glfwSetErrorCallback([](int, const char* text) { std::fprintf(stderr, "wisp: GLFW: %s\n", text); });
    if (!glfwInit())
        throw UserError("cannot open a window: GLFW could not initialise (is the display reachable?)");
    struct GlfwGuard {
        ~GlfwGuard() { glfwTerminate(); }
    } glfwGuard;
    if (!glfwVulkanSupported())
        throw UserError("cannot open a window: GLFW finds no Vulkan loader with surface support");

    vk::ContextOptions contextOptions = options.context;
    uint32_t glfwCount = 0;
    const char** glfwExtensions = glfwGetRequiredInstanceExtensions(&glfwCount);
    for (uint32_t i = 0; i < glfwCount; ++i)
        contextOptions.instanceExtensions.emplace_back(glfwExtensions[i]);
    contextOptions.presentation = true;
    vk::Context ctx(contextOptions);

    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    GLFWwindow* window = glfwCreateWindow(int(options.settings.width), int(options.settings.height),
                                          ("Wisp - " + head.description.name).c_str(), nullptr, nullptr);
    if (!window)
        throw UserError("cannot open a window of " + std::to_string(options.settings.width) + "x" +
                        std::to_string(options.settings.height));
    struct WindowGuard {
        GLFWwindow* w;
        ~WindowGuard() { glfwDestroyWindow(w); }
    } windowGuard{window};

    VkSurfaceKHR surface = VK_NULL_HANDLE;
    VK_CHECK(glfwCreateWindowSurface(ctx.instance(), window, nullptr, &surface));
    struct SurfaceGuard {
        VkInstance i;
        VkSurfaceKHR s;
        ~SurfaceGuard() { vkDestroySurfaceKHR(i, s, nullptr); }
    } surfaceGuard{ctx.instance(), surface};
    VkBool32 presentable = VK_FALSE;
    VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(ctx.physicalDevice(), ctx.queueFamily(), surface, &presentable));
    if (!presentable)
        throw UserError("the Vulkan device '" + ctx.report().name + "' cannot present to this window");

    constexpr uint32_t kFramesInFlight = 2;
    int fbWidth = 0, fbHeight = 0;
    glfwGetFramebufferSize(window, &fbWidth, &fbHeight);
    RenderSettings settings = options.settings;
    settings.width = uint32_t(std::max(fbWidth, 1));
    settings.height = uint32_t(std::max(fbHeight, 1));

    Swapchain swapchain;
    createSwapchain(ctx, surface, {settings.width, settings.height}, swapchain);
    settings.width = swapchain.extent.width;
    settings.height = swapchain.extent.height;
    std::unique_ptr<GpuSolver> solver;
    SimSetup setup;
    if (options.scene->strands.strandCount() > 0) {
        setup = makeSimSetup(options.sim, options.scene->strands, options.scene->gpuColliders, options.scene->unitsPerMetre);
        solver = std::make_unique<GpuSolver>(ctx, options.scene->strands, setup, glm::mat4(1.0f));
    }
    // The renderer is remade, pipelines and all, when the shaders are reloaded.
    auto makeRenderer = [&](const RenderSettings& s) {
        auto r = std::make_unique<Renderer>(ctx, s, kFramesInFlight);
        r->setHead(head);
        if (solver)
            r->attachHair(*solver, options.scene->strands, options.scene->unitsPerMetre);
        r->showLightMarker(true);
        return r;
    };
    std::unique_ptr<Renderer> rendererOwner = makeRenderer(settings);
    Renderer* renderer = rendererOwner.get();
    const float unitsPerMetre = options.scene->unitsPerMetre;
    std::vector<ScriptEvent> script;
    if (!options.script.empty())
        script = loadScript(options.script);
    constexpr uint32_t kMaxStepsPerFrame = 8;  // beyond this the simulation slows down instead of spiralling
    const float stepSeconds = 1.0f / options.sim.stepHz;
    const uint32_t scriptedStepsPerFrame = std::max(1u, uint32_t(std::lround(options.sim.stepHz / 60.0f)));
    uint64_t stepsDone = 0;
    double pendingSeconds = 0.0;
    bool paused = false;
    Frame frame(ctx, kFramesInFlight);
    auto present = std::make_unique<PresentBlitPass>(renderer->target());
    std::unique_ptr<ReadbackPass> readback;
    uint32_t screenshots = 0;
    std::vector<vk::Semaphore> acquired;
    for (uint32_t i = 0; i < kFramesInFlight; ++i)
        acquired.push_back(ctx.createSemaphore("window.acquired"));

    Viewer viewer(OrbitCamera::framing(renderer->sceneBounds(), float(settings.width) / float(settings.height)),
                  renderer->sceneBounds(), options.sphere, settings.light, options.sim.wind);
    Input input{.viewer = &viewer};
    glfwSetWindowUserPointer(window, &input);
    glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) {
        Input* in = static_cast<Input*>(glfwGetWindowUserPointer(w));
        if (!in->ui || !in->ui->wantsMouse())
            in->viewer->camera().zoom(std::pow(0.9f, float(dy)));
    });
    glfwSetKeyCallback(window, [](GLFWwindow* w, int glfwKey, int, int action, int) {
        Input* in = static_cast<Input*>(glfwGetWindowUserPointer(w));
        ViewerKey key;
        if (!viewerKeyOf(glfwKey, key))
            return;
        if (in->ui && in->ui->wantsKeyboard() && action == GLFW_PRESS)
            return;  // typing into the panel
        if (action == GLFW_PRESS)
            in->viewer->press(key);
        else if (action == GLFW_RELEASE)
            in->viewer->release(key);
    });
    glm::vec3 windApplied = options.sim.wind;
    std::string title;
    const OrbitCamera framing = OrbitCamera::framing(renderer->sceneBounds(), float(settings.width) / float(settings.height));
    SceneTimeline timeline = options.timeline;
    viewer.setPlaying(options.sceneLength > 0.0);
    std::filesystem::path lastSaved;
    uint32_t scenesSaved = 0;
    // After the window's callbacks: ImGui's GLFW backend chains them.
    UiOverlay ui(ctx, window, kFramesInFlight);
    ui.setTarget(renderer->target());
    input.ui = &ui;
    SimSettings sim = options.sim;
    // Settings edited in the panel: most apply in the next frame; a few rebuild what they size.
    RenderSettings pendingRender;
    SimSettings pendingSim;
    enum class Change { None, Live, Renderer, Solver } change = Change::None;
    auto rebuildRenderer = [&](const RenderSettings& s) {
        frame.waitIdle();
        present.reset();
        rendererOwner.reset();
        rendererOwner = makeRenderer(s);
        renderer = rendererOwner.get();
        present = std::make_unique<PresentBlitPass>(renderer->target());
        ui.setTarget(renderer->target());
    };

    bool rebuild = false;
    uint32_t framesDrawn = 0;
    auto lastFrame = std::chrono::steady_clock::now();
    while (!glfwWindowShouldClose(window)) {
        glfwPollEvents();
        glfwGetFramebufferSize(window, &fbWidth, &fbHeight);
        if (fbWidth == 0 || fbHeight == 0) {  // minimized: draw nothing until restored
            glfwWaitEvents();
            continue;
        }
        if (rebuild || uint32_t(fbWidth) != swapchain.extent.width || uint32_t(fbHeight) != swapchain.extent.height) {
            frame.waitIdle();
            createSwapchain(ctx, surface, {uint32_t(fbWidth), uint32_t(fbHeight)}, swapchain);
            renderer->resize(swapchain.extent);
            ui.setTarget(renderer->target());
            rebuild = false;
        }
        if (viewer.takeReload()) {
            frame.waitIdle();
            if (rebuildShaders()) {
                rebuildRenderer(renderer->settings());
                std::fprintf(stderr, "wisp: shaders reloaded\n");
            } else {
                std::fprintf(stderr, "wisp: the shader build failed; the previous shaders stay\n");
            }
        }
        if (viewer.takeReset() && solver) {
            frame.waitIdle();
            solver->reset(viewer.headTransform());
        }

        // Orbit, pan and the drags follow the mouse while a button is held.
        double x = 0.0, y = 0.0;
        glfwGetCursorPos(window, &x, &y);
        bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
        bool middle = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
        bool rightButton = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
        bool shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS || glfwGetKey(window, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
        float dx = float(x - input.lastX), dy = float(y - input.lastY);
        if (ui.wantsMouse())
            left = middle = rightButton = false;  // the panel has the mouse
        OrbitCamera& camera = viewer.camera();
        if (left && input.orbiting)
            viewer.orbit(dx, dy);
        if (middle && input.panning) {
            float unitsPerPixel = 2.0f * camera.distance * std::tan(glm::radians(camera.fovYDeg) * 0.5f) / float(fbHeight);
            camera.pan(-dx * unitsPerPixel, dy * unitsPerPixel);
        }
        if (rightButton && input.dragging) {
            if (shift)
                viewer.dragLight(dx, dy);
            else
                viewer.dragSphere(dx, dy, float(fbHeight));
        }
        input.orbiting = left;
        input.panning = middle;
        input.dragging = rightButton;
        input.lastX = x;
        input.lastY = y;
        std::vector<std::string> scriptedSets = playScript(script, framesDrawn, viewer, float(fbHeight));
        if (viewer.quit())
            glfwSetWindowShouldClose(window, GLFW_TRUE);

        // The panel, built before the frame begins so that what it changes applies to this frame.
        PanelData panel{.status = viewer.status(), .help = viewerHelp(), .counts = {}, .passes = {}};
        if (solver) {
            HairDrawCounts c = renderer->hairCounts();
            OitStats oit = renderer->oitStats(framesDrawn % kFramesInFlight);
            if (oit.overflow > 0 && oit.automatic && oit.capacity < oit.limit) {
                frame.waitIdle();  // the automatic pool grows for the next frame
                renderer->growOit(oit);
            }
            panel.counts.push_back("guides " + std::to_string(c.guides) + " x " + std::to_string(options.scene->strands.verticesPerStrand) +
                                   " vertices, simulated");
            panel.counts.push_back("strands drawn " + std::to_string(c.strands()) + " (" + std::to_string(c.strandsPerGuide) +
                                   " per guide, before LOD), segments " + std::to_string(c.segments()));
            if (oit.capacity > 0)
                panel.counts.push_back("OIT fragments " + std::to_string(oit.fragments) + " of a pool of " +
                                       std::to_string(oit.capacity) + ", dropped " + std::to_string(oit.overflow));
        }
        for (const vk::ScopeTime& t : frame.timings())
            panel.passes.emplace_back(t.name, t.milliseconds);
        pendingRender = renderer->settings();
        pendingSim = sim;
        change = Change::None;
        auto applyFromPanel = [&](const std::string& name, const std::string& text) -> std::string {
            static const std::set<std::string> solverSettings = {"step_hz", "substeps", "friction", "grid"};
            static const std::set<std::string> sizingSettings = {"shadow_size", "transparency", "oit_nodes_per_pixel", "samples"};
            try {
                applySetting({nullptr, &pendingSim, &pendingRender}, name + "=" + text);
            } catch (const UserError& e) {
                std::string why = e.what();
                if (why.find("does not use it") != std::string::npos)
                    return "the hair is grown at start: restart 'wisp view' with --set " + name + "=" + text;
                return why;
            }
            Change c = solverSettings.count(name) ? Change::Solver : sizingSettings.count(name) ? Change::Renderer : Change::Live;
            change = std::max(change, c);
            return "";
        };
        auto valueForPanel = [&](const std::string& name) -> std::string {
            RenderSettings r = renderer->settings();
            SimSettings m = sim;
            for (const SettingSpec& spec : settingSpecs())
                if (spec.name == name)
                    return spec.get({nullptr, &m, &r});
            return "";
        };
        ui.build(panel, applyFromPanel, valueForPanel, viewer.helpShown());
        for (const std::string& assignment : scriptedSets) {  // as if typed into the panel
            size_t eq = assignment.find('=');
            std::string error = applyFromPanel(assignment.substr(0, eq), assignment.substr(eq + 1));
            if (!error.empty())
                throw UserError("--script: " + assignment + ": " + error);
        }
        if (viewer.takeSave()) {  // F2: the window's state as a scene of one key
            char name[64];
            std::snprintf(name, sizeof(name), "wisp-scene-%03u.json", ++scenesSaved);
            std::filesystem::path out = std::filesystem::absolute(name);
            Scene saved;
            saved.description = "saved by wisp view";
            if (!options.headFile.empty())
                saved.head = scenePathText(out, std::filesystem::absolute(options.headFile));
            const HairOptions& h = options.hair;
            if (h.hairFiles.empty()) {
                saved.hair.guides = h.growth.guides;
                saved.hair.vertices = h.growth.verticesPerStrand;
                saved.hair.seed = h.growth.seed;
                saved.hair.hairLength = h.growth.lengthMetres;
                saved.hair.lengthVariation = h.growth.lengthVariation;
                saved.hair.curl = h.growth.curlRadiusMetres;
                saved.hair.poisson = h.growth.poissonDisk;
            } else {
                for (const std::string& f : h.hairFiles)
                    saved.hair.files.push_back({.path = scenePathText(out, std::filesystem::absolute(f))});
            }
            RenderSettings current = renderer->settings();
            saved.settings = currentSettings({nullptr, &sim, &current});
            SceneState state{.camera = cameraPoseOf(framing, viewer.camera()),
                             .sphere = viewer.sphere(),
                             .light = viewer.light(),
                             .wind = viewer.wind(),
                             .headYawDeg = viewer.headYawDeg()};
            saved.keys.push_back(sceneKey(0.0, state));
            saveScene(out, saved);
            lastSaved = out;
            std::printf("wisp: saved the scene %s\n", out.string().c_str());
        }
        if (viewer.takeLoad()) {  // F3: the last saved scene's settings and keys (head and hair stay)
            if (lastSaved.empty()) {
                std::fprintf(stderr, "wisp: no scene saved yet (F2 saves one; 'wisp view --scene FILE' opens any)\n");
            } else {
                Scene loaded = loadScene(lastSaved);
                for (const auto& [name, value] : loaded.settings)
                    if (std::string error = applyFromPanel(name, value); !error.empty())
                        std::fprintf(stderr, "wisp: %s: %s=%s: %s\n", lastSaved.string().c_str(), name.c_str(), value.c_str(),
                                     error.c_str());
                SceneState base{.camera = cameraPoseOf(framing, viewer.camera()),
                                .sphere = viewer.sphere(),
                                .light = viewer.light(),
                                .wind = viewer.wind(),
                                .headYawDeg = viewer.headYawDeg()};
                timeline = SceneTimeline(loaded.keys, loaded.interpolation, base);
                SceneState s0 = timeline.at(0.0);
                viewer.pose(poseCamera(framing, s0.camera), s0.sphere, s0.light, s0.wind, s0.headYawDeg);
                std::printf("wisp: loaded the scene %s (its head and hair are not reloaded)\n", lastSaved.string().c_str());
            }
        }
        if (change == Change::Live) {
            renderer->settings() = pendingRender;
        } else if (change == Change::Renderer) {
            rebuildRenderer(pendingRender);
        } else if (change == Change::Solver && solver) {
            frame.waitIdle();
            sim = pendingSim;
            setup = makeSimSetup(sim, options.scene->strands, options.scene->gpuColliders, options.scene->unitsPerMetre);
            rendererOwner.reset();  // it holds the old solver
            solver = std::make_unique<GpuSolver>(ctx, options.scene->strands, setup, viewer.headTransform());
            windApplied = sim.wind;
            rebuildRenderer(pendingRender);
        }

        std::vector<TrackedImage*> transient = renderer->transientImages();
        FrameContext& fc = frame.begin(transient);
        VkSemaphore acquire = acquired[fc.slot];
        uint32_t imageIndex = 0;
        VkResult got = vkAcquireNextImageKHR(ctx.device(), swapchain.handle, UINT64_MAX, acquire, VK_NULL_HANDLE, &imageIndex);
        if (got == VK_ERROR_OUT_OF_DATE_KHR) {
            frame.submit(fc);  // empty, keeps the slot's fence in step
            rebuild = true;
            continue;
        }
        if (got != VK_SUBOPTIMAL_KHR)
            VK_CHECK(got);

        // The simulation advances in fixed steps only: real time decides how many are due (a
        // scripted run, --frames, takes one 60 Hz frame's worth each frame, so it repeats).
        auto now = std::chrono::steady_clock::now();
        double elapsed = std::chrono::duration<double>(now - lastFrame).count();
        lastFrame = now;
        float frameSeconds = options.maxFrames > 0 ? 1.0f / 60.0f : float(std::min(elapsed, 0.1));
        viewer.update(frameSeconds);
        paused = viewer.paused();
        if (viewer.playing()) {  // the scene's keys drive the camera, sphere, light, wind and head
            SceneState st = timeline.at(double(stepsDone) * stepSeconds);
            viewer.pose(poseCamera(framing, st.camera), st.sphere, st.light, st.wind, st.headYawDeg);
        }
        uint32_t due = 0;
        if (solver) {
            if (paused) {
                due = viewer.takeSteps();
            } else if (options.maxFrames > 0) {
                due = scriptedStepsPerFrame;
            } else {
                pendingSeconds += elapsed;
                due = uint32_t(pendingSeconds / stepSeconds);
                pendingSeconds -= double(due) * stepSeconds;
                if (due > kMaxStepsPerFrame) {
                    due = kMaxStepsPerFrame;
                    pendingSeconds = 0.0;
                }
            }
            glm::vec3 wind = viewer.wind() * unitsPerMetre;
            if (wind != windApplied) {
                solver->setWind(wind);
                windApplied = wind;
            }
        }
        glm::mat4 headTransform = viewer.headTransform();
        glm::vec4 sphere = viewer.sphere();
        std::vector<gpu::SimStep> steps;
        for (uint32_t k = 0; k < due; ++k)
            steps.push_back(makeStep(setup, headTransform, sphere, float(stepsDone + k) * stepSeconds));
        stepsDone += due;
        renderer->setSteps(std::move(steps));
        renderer->settings().light = viewer.light();
        renderer->setHeadTransform(headTransform);
        renderer->setSphere(sphere);
        renderer->prepare(fc, camera, float(stepsDone) * stepSeconds);
        std::string newTitle = "Wisp - " + viewer.status() + (viewer.helpShown() ? "  |  " + viewerHelp() : "");
        if (newTitle != title) {
            title = newTitle;
            glfwSetWindowTitle(window, title.c_str());
        }
        TrackedImage& swapImage = swapchain.images[imageIndex];
        swapImage.layout = VK_IMAGE_LAYOUT_UNDEFINED;  // its previous contents are not needed
        swapImage.stages = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;  // wait for the acquire semaphore's stage
        swapImage.accesses = VK_ACCESS_2_NONE;
        swapImage.written = false;
        present->setSwapchainImage(swapImage, swapchain.extent);
        std::vector<Pass*> passes = renderer->passes();
        bool last = options.maxFrames > 0 && framesDrawn + 1 >= options.maxFrames;
        bool shot = viewer.takeScreenshot();
        std::unique_ptr<ReadbackPass> shotReadback;
        // Screenshots are the scene, taken before the panel is drawn over it.
        if (shot) {
            shotReadback = std::make_unique<ReadbackPass>(ctx, renderer->target());
            passes.push_back(shotReadback.get());
        }
        if (last && !options.screenshot.empty() && !options.screenshotPanel) {
            readback = std::make_unique<ReadbackPass>(ctx, renderer->target());
            passes.push_back(readback.get());
        }
        passes.push_back(&ui);
        if (last && !options.screenshot.empty() && options.screenshotPanel) {
            readback = std::make_unique<ReadbackPass>(ctx, renderer->target());
            passes.push_back(readback.get());
        }
        passes.push_back(present.get());
        frame.run(fc, passes);
        frame.transition(fc, swapImage, Access::Present);
        VkSemaphore done = swapchain.renderDone[imageIndex];
        frame.submit(fc, acquire, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, done);

        VkPresentInfoKHR presentInfo{.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR,
                                     .waitSemaphoreCount = 1,
                                     .pWaitSemaphores = &done,
                                     .swapchainCount = 1,
                                     .pSwapchains = &swapchain.handle,
                                     .pImageIndices = &imageIndex};
        VkResult presented = vkQueuePresentKHR(ctx.queue(), &presentInfo);
        if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR)
            rebuild = true;
        else
            VK_CHECK(presented);
        ++framesDrawn;
        if (shot) {  // P: the frame as drawn, beside the working folder's other files
            frame.waitIdle();
            char name[64];
            std::snprintf(name, sizeof(name), "wisp-screenshot-%03u.png", ++screenshots);
            VkExtent2D e = renderer->target().extent();
            writePng(name, e.width, e.height, shotReadback->pixels());
            std::printf("wisp: screenshot %s\n", name);
        }
        if (last)
            glfwSetWindowShouldClose(window, GLFW_TRUE);
    }
    frame.waitIdle();
    if (readback) {
        VkExtent2D e = renderer->target().extent();
        writePng(options.screenshot, e.width, e.height, readback->pixels());
    }
    std::printf("wisp: closed after %u frames: %s\n", framesDrawn, viewer.status().c_str());
    uint32_t messages = ctx.validationMessages();
    if (messages > 0) {
        std::fprintf(stderr, "wisp: %u Vulkan validation messages (printed above)\n", messages);
        return kExitInternalError;
    }
    return 0;
}

}  // namespace wisp
