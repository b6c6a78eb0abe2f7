// app/window/window.cpp: `wisp view` as a small class: GLFW (the window, its surface, the keys and the
// mouse), the swapchain (app/window/swapchain.h), the renderer over a hair session, the panel, and the
// frame: the input applied, the panel's edits applied (live, or rebuilding the renderer or the
// solver), the steps due, the passes, present. Scenes are saved and loaded by app/window/window_scene.h.
#include "app/window/window.h"

#include "app/commands/command.h"
#include "app/image/image_io.h"
#include "app/session/hair_session.h"
#include "app/settings/settings_table.h"
#include "app/window/swapchain.h"
#include "app/window/ui.h"
#include "app/window/viewer.h"
#include "app/window/window_scene.h"
#include "core/error.h"
#include "gpu/check.h"
#include "gpu/frame.h"
#include "gpu/timestamps.h"
#include "renderer/renderer.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>

namespace wisp {

namespace {

constexpr uint32_t kFramesInFlight = 2;
constexpr uint32_t kMaxStepsPerFrame = 8; // beyond this the simulation slows down instead of spiralling
constexpr float kScriptedFps = 60.0f;     // a scripted run (--frames) takes this rate's steps a frame

// GLFW keys to the viewer's (the one table of what each key does is app/window/viewer.cpp).
bool viewerKeyOf(int glfwKey, ViewerKey& key)
{
    switch (glfwKey) {
    case GLFW_KEY_LEFT:
        key = ViewerKey::SphereLeft;
        return true;
    case GLFW_KEY_RIGHT:
        key = ViewerKey::SphereRight;
        return true;
    case GLFW_KEY_UP:
        key = ViewerKey::SphereUp;
        return true;
    case GLFW_KEY_DOWN:
        key = ViewerKey::SphereDown;
        return true;
    case GLFW_KEY_PAGE_UP:
        key = ViewerKey::SphereNear;
        return true;
    case GLFW_KEY_PAGE_DOWN:
        key = ViewerKey::SphereFar;
        return true;
    case GLFW_KEY_J:
        key = ViewerKey::LightLeft;
        return true;
    case GLFW_KEY_L:
        key = ViewerKey::LightRight;
        return true;
    case GLFW_KEY_I:
        key = ViewerKey::LightUp;
        return true;
    case GLFW_KEY_K:
        key = ViewerKey::LightDown;
        return true;
    case GLFW_KEY_A:
        key = ViewerKey::HeadLeft;
        return true;
    case GLFW_KEY_D:
        key = ViewerKey::HeadRight;
        return true;
    case GLFW_KEY_W:
        key = ViewerKey::Wind;
        return true;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD:
        key = ViewerKey::WindStronger;
        return true;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT:
        key = ViewerKey::WindWeaker;
        return true;
    case GLFW_KEY_SPACE:
        key = ViewerKey::Pause;
        return true;
    case GLFW_KEY_N:
        key = ViewerKey::Step;
        return true;
    case GLFW_KEY_R:
        key = ViewerKey::Reset;
        return true;
    case GLFW_KEY_P:
        key = ViewerKey::Screenshot;
        return true;
    case GLFW_KEY_F5:
        key = ViewerKey::Reload;
        return true;
    case GLFW_KEY_O:
        key = ViewerKey::SphereToggle;
        return true;
    case GLFW_KEY_H:
        key = ViewerKey::Help;
        return true;
    case GLFW_KEY_ESCAPE:
        key = ViewerKey::Quit;
        return true;
    case GLFW_KEY_T:
        key = ViewerKey::Play;
        return true;
    case GLFW_KEY_F2:
        key = ViewerKey::SaveScene;
        return true;
    case GLFW_KEY_F3:
        key = ViewerKey::LoadScene;
        return true;
    default:
        return false;
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

// GLFW for the window's life: initialised first, terminated last.
struct GlfwLibrary {
    GlfwLibrary()
    {
        glfwSetErrorCallback([](int, const char* text) { std::fprintf(stderr, "wisp: GLFW: %s\n", text); });
        if (!glfwInit())
            throw UserError("cannot open a window: GLFW could not initialise (is the display reachable?)");
        if (!glfwVulkanSupported()) {
            glfwTerminate();
            throw UserError("cannot open a window: GLFW finds no Vulkan loader with surface support");
        }
    }
    ~GlfwLibrary() { glfwTerminate(); }
    GlfwLibrary(const GlfwLibrary&) = delete;
    GlfwLibrary& operator=(const GlfwLibrary&) = delete;
};

vk::ContextOptions presentingOptions(vk::ContextOptions options)
{
    uint32_t count = 0;
    const char** extensions = glfwGetRequiredInstanceExtensions(&count);
    for (uint32_t i = 0; i < count; ++i)
        options.instanceExtensions.emplace_back(extensions[i]);
    options.presentation = true;
    return options;
}

struct GlfwWindow {
    GLFWwindow* handle = nullptr;
    GlfwWindow(uint32_t width, uint32_t height, const std::string& title)
    {
        glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
        handle = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
        if (!handle)
            throw UserError("cannot open a window of " + std::to_string(width) + "x" + std::to_string(height));
    }
    ~GlfwWindow() { glfwDestroyWindow(handle); }
    GlfwWindow(const GlfwWindow&) = delete;
    GlfwWindow& operator=(const GlfwWindow&) = delete;
};

struct Surface {
    VkInstance instance;
    VkSurfaceKHR handle = VK_NULL_HANDLE;
    Surface(const vk::Context& ctx, GLFWwindow* window) : instance(ctx.instance())
    {
        VK_CHECK(glfwCreateWindowSurface(ctx.instance(), window, nullptr, &handle));
        VkBool32 presentable = VK_FALSE;
        VkResult r =
            vkGetPhysicalDeviceSurfaceSupportKHR(ctx.physicalDevice(), ctx.queueFamily(), handle, &presentable);
        if (r != VK_SUCCESS || !presentable) {
            vkDestroySurfaceKHR(instance, handle, nullptr);
            VK_CHECK(r);
            throw UserError("the Vulkan device '" + ctx.report().name + "' cannot present to this window");
        }
    }
    ~Surface() { vkDestroySurfaceKHR(instance, handle, nullptr); }
    Surface(const Surface&) = delete;
    Surface& operator=(const Surface&) = delete;
};

// The mouse as the last frame left it.
struct Mouse {
    double lastX = 0.0, lastY = 0.0;
    bool orbiting = false, panning = false, dragging = false;
};

class Window {
public:
    explicit Window(WindowOptions options);
    int run();

private:
    VkExtent2D framebufferSize() const;
    void rebuildRenderer(const RenderSettings& settings);
    void followMouse(float viewportHeight);
    void buildPanel(const std::vector<std::string>& scriptedSets);
    std::string applyFromPanel(const SettingSpec& spec, const SettingValue& value);
    void saveOrLoadScene();
    void applyEdits();
    void drawFrame();
    SceneState now();

    WindowOptions options_;
    GlfwLibrary glfw_;
    vk::Context ctx_;
    GlfwWindow window_;
    Surface surface_;
    Swapchain swapchain_;
    HairSession session_;
    std::unique_ptr<Renderer> renderer_;
    std::vector<ScriptEvent> script_;
    Frame frame_;
    std::unique_ptr<PresentBlitPass> present_;
    std::unique_ptr<ReadbackPass> readback_; // the --screenshot of the last frame
    std::vector<vk::Semaphore> acquired_;
    Viewer viewer_;
    OrbitCamera framing_;
    Mouse mouse_;
    UiOverlay ui_; // after the window's callbacks: ImGui's GLFW backend chains them

    SceneTimeline timeline_;              // a scene's keys, played while the viewer is playing
    SimSettings sim_;                     // what the solver runs with
    Settings pending_;                    // the settings as the panel edits them this frame
    std::optional<SettingChange> change_; // the largest change the edits need
    bool rebuildSwapchain_ = false;
    uint32_t framesDrawn_ = 0, screenshots_ = 0, scenesSaved_ = 0;
    std::filesystem::path lastSaved_;
    std::string title_;
    std::chrono::steady_clock::time_point lastFrame_ = std::chrono::steady_clock::now();
};

Window::Window(WindowOptions options)
    : options_(std::move(options)), glfw_(), ctx_(presentingOptions(options_.context)),
      window_(options_.settings.render.width, options_.settings.render.height,
              "Wisp - " + options_.scene.head.description.name),
      surface_(ctx_, window_.handle), swapchain_(ctx_, surface_.handle, framebufferSize()),
      session_(ctx_, std::move(options_.scene), options_.settings.sim, options_.timeline, options_.source),
      frame_(ctx_, kFramesInFlight),
      viewer_(OrbitCamera::framing(session_.headBounds(),
                                   float(swapchain_.extent().width) / float(swapchain_.extent().height)),
              session_.headBounds(), options_.sphere, options_.settings.render.light, options_.settings.sim.wind),
      framing_(viewer_.camera()), ui_(ctx_, window_.handle, kFramesInFlight), timeline_(options_.timeline),
      sim_(options_.settings.sim)
{
    rebuildRenderer(options_.settings.render);
    if (!options_.script.empty())
        script_ = loadScript(options_.script);
    for (uint32_t i = 0; i < kFramesInFlight; ++i)
        acquired_.push_back(ctx_.createSemaphore("window.acquired"));
    viewer_.setPlaying(options_.sceneLength > 0.0);

    glfwSetWindowUserPointer(window_.handle, this);
    glfwSetScrollCallback(window_.handle, [](GLFWwindow* w, double, double dy) {
        Window* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
        if (!self->ui_.wantsMouse())
            self->viewer_.camera().zoom(std::pow(0.9f, float(dy)));
    });
    glfwSetKeyCallback(window_.handle, [](GLFWwindow* w, int glfwKey, int, int action, int) {
        Window* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
        ViewerKey key;
        if (!viewerKeyOf(glfwKey, key))
            return;
        if (self->ui_.wantsKeyboard() && action == GLFW_PRESS)
            return; // typing into the panel
        if (action == GLFW_PRESS)
            self->viewer_.press(key);
        else if (action == GLFW_RELEASE)
            self->viewer_.release(key);
    });
}

VkExtent2D Window::framebufferSize() const
{
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_.handle, &width, &height);
    return {uint32_t(std::max(width, 1)), uint32_t(std::max(height, 1))};
}

// The renderer is made again, pipelines and all, when a setting sizes it, when the solver was
// made again (it holds it), and when the shaders are reloaded.
void Window::rebuildRenderer(const RenderSettings& settings)
{
    frame_.waitIdle();
    present_.reset();
    renderer_.reset();
    RenderSettings s = settings;
    s.width = swapchain_.extent().width;
    s.height = swapchain_.extent().height;
    renderer_ = std::make_unique<Renderer>(ctx_, s, kFramesInFlight);
    renderer_->setHead(session_.scene().head);
    session_.attachTo(*renderer_);
    renderer_->showLightMarker(true);
    present_ = std::make_unique<PresentBlitPass>(renderer_->target());
    ui_.setTarget(renderer_->target());
}

// Orbit, pan and the drags follow the mouse while a button is held (not while the panel has it).
void Window::followMouse(float viewportHeight)
{
    GLFWwindow* w = window_.handle;
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(w, &x, &y);
    bool left = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    bool middle = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    bool right = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    bool shift = glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS || glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
    float dx = float(x - mouse_.lastX), dy = float(y - mouse_.lastY);
    if (ui_.wantsMouse())
        left = middle = right = false;
    OrbitCamera& camera = viewer_.camera();
    if (left && mouse_.orbiting)
        viewer_.orbit(dx, dy);
    if (middle && mouse_.panning) {
        float unitsPerPixel = 2.0f * camera.distance * std::tan(glm::radians(camera.fovYDeg) * 0.5f) / viewportHeight;
        camera.pan(-dx * unitsPerPixel, dy * unitsPerPixel);
    }
    if (right && mouse_.dragging) {
        if (shift)
            viewer_.dragLight(dx, dy);
        else
            viewer_.dragSphere(dx, dy, viewportHeight);
    }
    mouse_ = {.lastX = x, .lastY = y, .orbiting = left, .panning = middle, .dragging = right};
}

std::string Window::applyFromPanel(const SettingSpec& spec, const SettingValue& value)
{
    SettingEdit edit = editSetting(pending_, spec, value);
    if (!edit.error.empty())
        return edit.error;
    change_ = std::max(change_.value_or(SettingChange::Live), edit.change);
    // Samples the device lacks: drawn with the most it has below them, said as at the start (the
    // panel then shows what is drawn), never the asked number drawn as fewer without a word.
    if (spec.name == "samples") {
        if (std::string note = useDeviceSamples(pending_.render, ctx_.report()); !note.empty())
            std::fprintf(stderr, "%s\n", note.c_str());
    }
    return "";
}

// The panel, built before the frame begins so that what it changes applies to this frame; a
// script's `set` lines go the panel's way.
void Window::buildPanel(const std::vector<std::string>& scriptedSets)
{
    PanelData panel{.status = viewer_.status(), .help = viewerHelp(), .counts = {}, .passes = {}};
    if (session_.hasHair()) {
        StrandCounts c = renderer_->hairCounts();
        OitStats oit = renderer_->oitStats(framesDrawn_ % kFramesInFlight);
        if (oit.overflow > 0 && oit.automatic && oit.capacity < oit.limit) {
            frame_.waitIdle(); // the automatic pool grows for the next frame
            renderer_->growOit(oit);
        }
        panel.counts.push_back("guides " + std::to_string(c.guides) + " x " +
                               std::to_string(session_.scene().strands.verticesPerStrand) + " vertices, simulated");
        panel.counts.push_back("strands drawn " + std::to_string(c.strands()) + " (" +
                               std::to_string(c.strandsPerGuide) + " per guide, before LOD), segments " +
                               std::to_string(c.segments()));
        // The hair's fragments as the path that draws it holds them (the other reports zeros).
        if (renderer_->hairRaster() == HairRaster::Compute) {
            RasterStats raster = renderer_->rasterStats(framesDrawn_ % kFramesInFlight);
            if (raster.capacity > 0)
                panel.counts.push_back(describeRasterStats(raster));
        } else if (oit.capacity > 0) {
            panel.counts.push_back("OIT fragments " + std::to_string(oit.fragments) + " of a pool of " +
                                   std::to_string(oit.capacity) + ", dropped " + std::to_string(oit.overflow));
        }
    }
    for (const vk::ScopeTime& t : vk::timingsByName(frame_.timings()))
        panel.passes.emplace_back(t.name, t.milliseconds);
    // What the panel shows: the settings as they are now (the viewer's light and wind included).
    pending_ = Settings{.growth = options_.settings.growth, .sim = sim_, .render = renderer_->settings()};
    pending_.render.light = viewer_.light();
    pending_.sim.wind = viewer_.wind();
    const Settings shown = pending_;
    change_.reset();
    auto apply = [this](const SettingSpec& spec, const SettingValue& value) { return applyFromPanel(spec, value); };
    ui_.build(panel, shown, apply, viewer_.helpShown());
    for (const std::string& assignment : scriptedSets) {
        size_t eq = assignment.find('=');
        std::string name = assignment.substr(0, eq);
        std::string error;
        if (const SettingSpec* spec = findSetting(name)) {
            try {
                error = applyFromPanel(*spec, parseSetting(*spec, assignment.substr(eq + 1), name));
            } catch (const UserError& e) {
                error = e.what();
            }
        } else {
            error = "unknown setting '" + name + "' (see 'wisp settings')";
        }
        if (!error.empty())
            throw UserError("--script: " + assignment + ": " + error);
    }
}

SceneState Window::now()
{
    return {.camera = cameraPoseOf(framing_, viewer_.camera()),
            .sphere = viewer_.sphere(),
            .light = viewer_.light(),
            .wind = viewer_.wind(),
            .headYawDeg = viewer_.headYawDeg()};
}

// F2 saves the window's state as a scene; F3 loads the last one saved back.
void Window::saveOrLoadScene()
{
    if (viewer_.takeSave()) {
        Settings current{.growth = options_.settings.growth, .sim = sim_, .render = renderer_->settings()};
        current.sim.wind = viewer_.wind();
        lastSaved_ = saveWindowScene(++scenesSaved_, options_.source, current, now());
        std::printf("wisp: saved the scene %s\n", lastSaved_.string().c_str());
    }
    if (viewer_.takeLoad()) {
        if (lastSaved_.empty()) {
            std::fprintf(stderr, "wisp: no scene saved yet (F2 saves one; 'wisp view --scene FILE' opens any)\n");
            return;
        }
        auto apply = [this](const SettingSpec& spec, const SettingValue& value) { return applyFromPanel(spec, value); };
        timeline_ = loadWindowScene(lastSaved_, now(), apply);
        SceneState s0 = timeline_.at(0.0);
        viewer_.pose(poseCamera(framing_, s0.camera), s0.sphere, s0.light, s0.wind, s0.headYawDeg);
        std::printf("wisp: loaded the scene %s (its head and hair are not reloaded)\n", lastSaved_.string().c_str());
    }
}

// What the panel's edits need: live ones at once; the renderer made again for the settings that
// size it; the solver too (the session decides from what it packs), the renderer holding it.
void Window::applyEdits()
{
    if (!change_)
        return;
    viewer_.setLight(pending_.render.light); // the light and the wind are the viewer's
    viewer_.setWind(pending_.sim.wind);
    if (change_ == SettingChange::Solver) {
        frame_.waitIdle();
        present_.reset();
        renderer_.reset();
    }
    sim_ = pending_.sim;
    session_.setSim(sim_, viewer_.headTransform());
    if (change_ == SettingChange::Live)
        renderer_->settings() = pending_.render;
    else
        rebuildRenderer(pending_.render);
}

// One frame: the steps due (real time since the last image was acquired, or a scripted frame's
// worth), the passes (a screenshot's readback before the panel, or after it when asked), present.
void Window::drawFrame()
{
    std::vector<TrackedImage*> transient = renderer_->transientImages();
    FrameContext& fc = frame_.begin(transient);
    VkSemaphore acquire = acquired_[fc.slot];
    uint32_t imageIndex = 0;
    if (!swapchain_.acquire(acquire, imageIndex)) {
        frame_.submit(fc); // empty, keeps the slot's fence in step
        rebuildSwapchain_ = true;
        return;
    }
    auto acquiredAt = std::chrono::steady_clock::now();
    double elapsed = std::chrono::duration<double>(acquiredAt - lastFrame_).count();
    lastFrame_ = acquiredAt;

    // The simulation advances in fixed steps only: real time decides how many are due (a scripted
    // run, --frames, takes one 60 Hz frame's worth each frame, so it repeats).
    bool scripted = options_.maxFrames > 0;
    viewer_.update(scripted ? 1.0f / kScriptedFps : float(std::min(elapsed, 0.1)));
    if (viewer_.playing()) { // the scene's keys drive the camera, sphere, light, wind and head
        SceneState st = timeline_.at(session_.clock().seconds());
        viewer_.pose(poseCamera(framing_, st.camera), st.sphere, st.light, st.wind, st.headYawDeg);
    }
    uint32_t due = 0;
    if (session_.hasHair())
        due = viewer_.paused() ? viewer_.takeSteps()
              : scripted       ? session_.clock().stepsPerFrame(kScriptedFps)
                               : session_.clock().stepsDue(elapsed, kMaxStepsPerFrame);
    StepPose pose{.head = viewer_.headTransform(), .sphere = viewer_.sphere(), .wind = viewer_.wind()};
    // This frame's steps run beside its drawing (Renderer::setStepsAhead), so its picture shows the
    // hair as the last frame's steps left it: a frame late, and the physics off the frame's time.
    float drawn = session_.clock().stepStart(session_.clock().stepsDone()); // the moment the picture shows
    renderer_->setSteps({});
    renderer_->setStepsAhead(session_.nextSteps(due, pose));
    renderer_->settings().light = viewer_.light();
    renderer_->setHeadTransform(pose.head);
    renderer_->setSphere(pose.sphere);
    renderer_->prepare(fc, viewer_.camera(), drawn);
    std::string title = "Wisp - " + viewer_.status() + (viewer_.helpShown() ? "  |  " + viewerHelp() : "");
    if (title != title_) {
        title_ = title;
        glfwSetWindowTitle(window_.handle, title_.c_str());
    }

    TrackedImage& swapImage = swapchain_.beginImage(imageIndex);
    present_->setSwapchainImage(swapImage, swapchain_.extent());
    std::vector<Pass*> passes = renderer_->passes();
    bool last = scripted && framesDrawn_ + 1 >= options_.maxFrames;
    bool shot = viewer_.takeScreenshot();
    std::unique_ptr<ReadbackPass> shotReadback;
    if (shot) { // screenshots are the scene, taken before the panel is drawn over it
        shotReadback = std::make_unique<ReadbackPass>(ctx_, renderer_->target());
        passes.push_back(shotReadback.get());
    }
    bool keepLast = last && !options_.screenshot.empty();
    if (keepLast && !options_.screenshotPanel) {
        readback_ = std::make_unique<ReadbackPass>(ctx_, renderer_->target());
        passes.push_back(readback_.get());
    }
    passes.push_back(&ui_);
    if (keepLast && options_.screenshotPanel) {
        readback_ = std::make_unique<ReadbackPass>(ctx_, renderer_->target());
        passes.push_back(readback_.get());
    }
    passes.push_back(present_.get());
    frame_.run(fc, passes);
    frame_.transition(fc, swapImage, Access::Present);
    frame_.submit(fc, acquire, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, swapchain_.renderDone(imageIndex));
    if (!swapchain_.present(imageIndex))
        rebuildSwapchain_ = true;
    ++framesDrawn_;
    if (shot) { // P: the frame as drawn, beside the working folder's other files
        frame_.waitIdle();
        char name[64];
        std::snprintf(name, sizeof(name), "wisp-screenshot-%03u.png", ++screenshots_);
        VkExtent2D e = renderer_->target().extent();
        writePng(name, e.width, e.height, shotReadback->pixels());
        std::printf("wisp: screenshot %s\n", name);
    }
    if (last)
        glfwSetWindowShouldClose(window_.handle, GLFW_TRUE);
}

int Window::run()
{
    while (!glfwWindowShouldClose(window_.handle)) {
        glfwPollEvents();
        int width = 0, height = 0;
        glfwGetFramebufferSize(window_.handle, &width, &height);
        if (width == 0 || height == 0) { // minimized: draw nothing until restored
            glfwWaitEvents();
            continue;
        }
        if (rebuildSwapchain_ || uint32_t(width) != swapchain_.extent().width ||
            uint32_t(height) != swapchain_.extent().height) {
            frame_.waitIdle();
            swapchain_.recreate({uint32_t(width), uint32_t(height)});
            renderer_->resize(swapchain_.extent());
            ui_.setTarget(renderer_->target());
            rebuildSwapchain_ = false;
        }
        if (viewer_.takeReload()) { // F5: every shader, the solver's kernels and the renderer's pipelines
            frame_.waitIdle();
            if (rebuildShaders()) {
                session_.reloadShaders();
                rebuildRenderer(renderer_->settings());
                std::fprintf(stderr, "wisp: shaders reloaded\n");
            } else {
                std::fprintf(stderr, "wisp: the shader build failed; the previous shaders stay\n");
            }
        }
        if (viewer_.takeReset() && session_.hasHair()) {
            frame_.waitIdle();
            session_.reset(viewer_.headTransform());
        }
        followMouse(float(height));
        std::vector<std::string> scriptedSets = playScript(script_, framesDrawn_, viewer_, float(height));
        if (viewer_.quit())
            glfwSetWindowShouldClose(window_.handle, GLFW_TRUE);
        buildPanel(scriptedSets);
        saveOrLoadScene();
        applyEdits();
        drawFrame();
    }
    frame_.waitIdle();
    if (readback_) {
        VkExtent2D e = renderer_->target().extent();
        writePng(options_.screenshot, e.width, e.height, readback_->pixels());
    }
    std::printf("wisp: closed after %u frames: %s\n", framesDrawn_, viewer_.status().c_str());
    uint32_t messages = ctx_.validationMessages();
    if (messages > 0) {
        std::fprintf(stderr, "wisp: %u Vulkan validation messages (printed above)\n", messages);
        return kExitInternalError;
    }
    return 0;
}

} // namespace

void requireDisplay()
{
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((!display || !*display) && (!wayland || !*wayland))
        throw UserError("no display (DISPLAY and WAYLAND_DISPLAY are unset): 'wisp view' needs a window; "
                        "render offscreen with 'wisp render --out FILE.png' instead");
}

int runWindow(WindowOptions options)
{
    requireDisplay();
    if (!options.screenshot.empty())
        checkPngOutput(options.screenshot);
    Window window(std::move(options));
    return window.run();
}

} // namespace wisp
