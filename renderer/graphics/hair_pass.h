// renderer/graphics/hair_pass.h: the simulated guides drawn as a full head of hair: tessellation (Bezier,
// more strands per guide, deviations) -> geometry shader (camera-facing ribbons) -> fragments shaded
// with the model the `shading` setting names (Karis by default, Kajiya-Kay or the lookup tables:
// shaders/shared/hair_shading.h), reading the guides straight from the solver's buffers in the same frame.
#pragma once

#include "gpu/handle.h"
#include "gpu/pass.h"
#include "gpu/resources.h"
#include "physics/strand_set.h"
#include "renderer/settings.h"
#include "renderer/strand_draw.h"
#include "shaders/shared/strands.h"

#include <vector>

namespace wisp {

namespace vk {
class Context;
}
class RenderTarget;
class FrameUniforms;
class GpuSolver;
class LightMaps;
class Oit;
class HairLutImage;

// What a draw produces for given settings: the Vulkan limits split it into patches and instances,
// never cap it (the CLI and UI report these).
struct HairDrawCounts {
    uint32_t guides = 0;
    uint32_t strandsPerGuide = 0; // as drawn (before LOD)
    uint32_t divisions = 0;       // segments per strand
    uint32_t lengthChunks = 0;    // patches along a strand: ceil(divisions / 64)
    uint32_t strandsPerPatch = 0; // lines a patch holds: <= 64 and <= maxPatchVertices / (divisions + 1)
    uint32_t strandChunks = 0;    // instances: ceil(strands per guide / strandsPerPatch)
    uint32_t patchesPerDraw = 0;  // patches one draw holds: its tessellated vertices per instance
                                  // stay within gpu::kMaxTessVerticesPerDraw
    uint64_t patches() const { return uint64_t(guides) * lengthChunks; }
    uint64_t draws() const { return patchesPerDraw ? (patches() + patchesPerDraw - 1) / patchesPerDraw : 0; }
    uint64_t strands() const { return uint64_t(guides) * strandsPerGuide; }
    uint64_t segments() const { return strands() * divisions; }
};
HairDrawCounts hairDrawCounts(uint32_t guides, const StrandSettings& settings);

class HairPass : public Pass {
public:
    // The device memory for `guides` guides: a triangle of guides each.
    static constexpr uint64_t deviceBytes(uint64_t guides) { return guides * sizeof(glm::uvec4); }

    HairPass(const vk::Context& ctx, RenderTarget& target, FrameUniforms& uniforms, GpuSolver& solver,
             const StrandSet& strands);
    const char* name() const override { return "hair"; }
    void declare(PassIo& io) override;
    void record(VkCommandBuffer cmd, FrameContext& frame) override;

    // What the camera's draw reads and writes besides the target: the light's maps (always), and
    // in OIT mode the linked lists (null: MSAA coverage). Set before the first frame.
    void setLightMaps(LightMaps* maps) { lightMaps_ = maps; }
    void setOit(Oit* oit) { oit_ = oit; }
    // The lookup mode's tables (the Renderer's, shared with the compute path). Set before the first frame.
    void setLut(const HairLutImage* lut) { lut_ = lut; }
    // The guides the tessellation reads, for the passes that draw the hair from the light.
    void declareGuides(PassIo& io);
    enum class LightDraw { Depth, Opacity };
    // Draws the same hair from the light into the rendering the caller has begun.
    void recordFromLight(VkCommandBuffer cmd, FrameContext& frame, LightDraw draw);

    // This frame's strands for the camera and for the light's maps (fewer, wider: see
    // shadow_strands), drawn in `counts`' patches and instances.
    void setDraw(const StrandDraw& camera, const StrandDraw& light, const HairDrawCounts& counts);
    const HairDrawCounts& counts() const { return counts_; }
    // Pipeline statistics of the last recorded draw (after its frame completed): how many
    // tessellation evaluations, geometry-shader invocations and primitives the draw produced.
    struct Statistics {
        uint64_t tessEvaluations = 0;
        uint64_t geometryInvocations = 0;
        uint64_t geometryPrimitives = 0;
    };
    Statistics statistics() const;

private:
    const vk::Context& ctx_;
    RenderTarget& target_;
    FrameUniforms& uniforms_;
    GpuSolver& solver_;
    vk::DescriptorSetLayout setLayout_;
    vk::PipelineLayout layout_;
    vk::Pipeline pipeline_;        // camera, MSAA coverage
    vk::Pipeline oitPipeline_;     // camera, fragments into the linked lists
    vk::Pipeline depthPipeline_;   // light, depth only
    vk::Pipeline opacityPipeline_; // light, deep opacity layers
    LightMaps* lightMaps_ = nullptr;
    const HairLutImage* lut_ = nullptr;
    Oit* oit_ = nullptr;
    vk::Buffer triangles_;
    vk::QueryPool statistics_; // empty where the device has no pipeline statistics
    gpu::HairPush push_{};
    gpu::HairPush lightPush_{};
    // Binds `pipeline`, pushes the guide bindings plus `extra`, and draws every patch and instance.
    void draw(VkCommandBuffer cmd, FrameContext& frame, VkPipeline pipeline,
              const std::vector<VkWriteDescriptorSet>& extra, gpu::HairPush push);
    HairDrawCounts counts_;
};

} // namespace wisp
