// renderer/graphics/hair_pass.h: the simulated guides drawn as a full head of hair: tessellation (Bezier,
// more strands per guide, deviations) -> geometry shader (camera-facing ribbons) -> fragments shaded
// with the model the `shading` setting names (Karis by default, Kajiya-Kay or the lookup tables:
// shaders/shared/hair_shading.h), reading the guides straight from the solver's buffers in the same frame.
#pragma once

#include "gpu/handle.h"
#include "gpu/pass.h"
#include "gpu/resources.h"
#include "physics/strand_set.h"
#include "renderer/light_maps.h"
#include "renderer/settings.h"
#include "renderer/strand_draw.h"
#include "shaders/shared/strands.h"

#include <string>
#include <vector>

namespace wisp {

namespace vk {
class Context;
}
class RenderTarget;
class FrameUniforms;
class GpuSolver;
class Oit;
class HairLutImage;

// How the tessellation draws given counts: the Vulkan limits split them into patches and
// instances, never cap them.
struct HairDrawCounts : StrandCounts {
    uint32_t lengthChunks = 0;    // patches along a strand: ceil(divisions / 64)
    uint32_t strandsPerPatch = 0; // lines a patch holds: <= 64 and <= maxPatchVertices / (divisions + 1)
    uint32_t strandChunks = 0;    // instances: ceil(strands per guide / strandsPerPatch)
    uint32_t patchesPerDraw = 0;  // patches one draw holds: its tessellated vertices per instance
                                  // stay within gpu::kMaxTessVerticesPerDraw
    uint64_t patches() const { return uint64_t(guides) * lengthChunks; }
    uint64_t draws() const { return patchesPerDraw ? (patches() + patchesPerDraw - 1) / patchesPerDraw : 0; }
};
HairDrawCounts hairDrawCounts(uint32_t guides, const StrandSettings& settings);
// "drawn as P patches of up to N strands x D divisions (I instances, K draws)": what the
// tessellation made of the strands, for `wisp render` to print.
std::string describeHairDraw(const HairDrawCounts& counts);

class HairPass : public Pass, public LightHairDraw {
public:
    // `triangles`: each guide's triangle of guides (guideTriangles, physics/strand_set.h).
    HairPass(const vk::Context& ctx, RenderTarget& target, FrameUniforms& uniforms, GpuSolver& solver,
             const std::vector<glm::uvec4>& triangles);
    const char* name() const override { return "hair"; }
    void declare(PassIo& io) override;
    void record(VkCommandBuffer cmd, FrameContext& frame) override;

    // What the camera's draw reads and writes besides the target: the light's maps (always), and
    // in OIT mode the linked lists (null: MSAA coverage). Set before the first frame.
    void setLightMaps(LightMaps* maps) { lightMaps_ = maps; }
    void setOit(Oit* oit) { oit_ = oit; }
    // The lookup mode's tables (the Renderer's, shared with the compute path). Set before the first frame.
    void setLut(const HairLutImage* lut) { lut_ = lut; }
    // The light's maps' hair (LightHairDraw): the guides the tessellation reads, and the same hair
    // drawn from the light into the rendering the caller has begun.
    void declareFromLight(PassIo& io) override;
    void recordFromLight(VkCommandBuffer cmd, FrameContext& frame, LightMap map) override;

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
