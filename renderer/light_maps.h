// renderer/light_maps.h: what the key light sees, remade every frame: the head's and the hair's
// depth maps (the shadow pass) and the hair's deep opacity layers (the opacity pass), and the
// samplers the mesh and hair shaders read them through (shaders/light_visibility.glsl).
//   shadow:  head depth  <- meshes from the light (depth only, slope-scaled bias)
//            hair depth  <- hair from the light (the path's own draw: LightHairDraw)
//   opacity: layers      <- hair from the light again, additive, each fragment into the layer its
//                           depth falls in behind the texel's first hair depth (Yuksel & Keyser 2008)
// The compute path writes the hair's maps from its own kernels (renderer/compute/strand_raster.h).
#pragma once

#include "gpu/compute_stage.h"
#include "gpu/handle.h"
#include "gpu/pass.h"
#include "gpu/resources.h"

#include <glm/glm.hpp>

#include <array>
#include <vector>

namespace wisp {

namespace vk {
class Context;
}
class MeshPass;

// The maps a path's hair is drawn into by the light's graphics passes.
enum class LightMap { Depth, Opacity };

// What draws the hair into the light's maps inside the shadow and opacity passes' rendering: the
// graphics path's tessellation (renderer/graphics/hair_pass.h). The compute path writes the maps
// from its own kernels and gives these passes none.
class LightHairDraw {
public:
    virtual ~LightHairDraw() = default;
    // What the draw reads (the guides), declared into the pass that draws it.
    virtual void declareFromLight(PassIo& io) = 0;
    // Draws the hair into `map`, whose rendering the pass has begun.
    virtual void recordFromLight(VkCommandBuffer cmd, FrameContext& frame, LightMap map) = 0;
};

// What the head's depth from the light depends on: while it stays the same, the map drawn for an
// earlier frame still holds (the head is rigid; its shadow map is kept, as engines keep static
// casters' shadows).
struct HeadShadowKey {
    glm::mat4 lightViewProjection{1.0f};
    glm::mat4 headTransform{1.0f};
    glm::vec4 sphere{0.0f}; // the user's sphere casts too
    uint32_t enabled = 0;
    uint32_t size = 0;
    uint32_t pad0 = 0;
    uint32_t pad1 = 0;
};

class LightMaps {
public:
    static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
    static constexpr VkFormat kOpacityFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

    // The device memory of maps of `size`² texels: the head's and the hair's depth, the opacity layers.
    static constexpr VkFormat kDepthValueFormat = VK_FORMAT_R32_SFLOAT;
    // The device memory of maps of `size`² texels: the head's and the hair's depth, the hair's
    // depth as values (the compute path's), the opacity layers.
    static constexpr uint64_t deviceBytes(uint32_t size)
    {
        return uint64_t(size) * size *
               (2 * vk::formatBytes(kDepthFormat) + vk::formatBytes(kDepthValueFormat) +
                vk::formatBytes(kOpacityFormat));
    }

    LightMaps(const vk::Context& ctx, uint32_t size);
    // Recreates the maps at a new size; the device must be idle.
    void resize(uint32_t size);
    uint32_t size() const { return size_; }

    TrackedImage& headDepth() { return headTrack_; }
    TrackedImage& hairDepth() { return hairTrack_; }
    TrackedImage& opacity() { return opacityTrack_; }
    // The hair's first depth as an R32F image: the compute path writes it from its kernels (no copy
    // into the depth image), and the deep opacity lookups sample it instead of the depth image
    // while useHairDepthValues(true).
    TrackedImage& hairDepthValues() { return valuesTrack_; }
    const vk::Image& hairDepthValuesImage() const { return hairValues_; }
    void useHairDepthValues(bool values);
    bool hairDepthValuesUsed() const { return values_; }
    const vk::Image& headDepthImage() const { return headDepth_; }
    const vk::Image& hairDepthImage() const { return hairDepth_; }
    const vk::Image& opacityImage() const { return opacity_; }
    // The hair's maps are remade every frame; the head's depth only when its key changes.
    std::vector<TrackedImage*> transientImages() { return {&hairTrack_, &valuesTrack_, &opacityTrack_}; }
    // This frame's key for the head's depth (before the frame's passes are declared).
    void setHeadKey(const HeadShadowKey& key);
    bool headDepthStale() const { return headStale_; }
    void headDepthDrawn()
    {
        drawnKey_ = key_;
        headStale_ = false;
    }

    // For a pass whose shaders read the maps: the accesses to declare, and the descriptor
    // writes for bindings kBindingShadowHead..kBindingOpacity (valid while this object lives).
    void declareRead(PassIo& io, Access access = Access::GraphicsSampled);
    std::array<VkWriteDescriptorSet, 4> descriptorWrites() const;
    // For a compute stage whose kernels read the maps: its entries for the same bindings, sampled
    // in compute (the hair's depth under two bindings is declared once).
    std::array<StageUse, 4> computeReads();
    // The hair depth alone, for the opacity pass (binding kBindingHairDepth).
    VkWriteDescriptorSet hairDepthWrite() const;

    // Begins rendering into one map, cleared (depth 1, opacity 0), with its viewport.
    void beginDepth(VkCommandBuffer cmd, const vk::Image& image) const;
    void beginOpacity(VkCommandBuffer cmd) const;

private:
    const vk::Context& ctx_;
    uint32_t size_ = 0;
    vk::Image headDepth_, hairDepth_, hairValues_, opacity_;
    TrackedImage headTrack_, hairTrack_, valuesTrack_, opacityTrack_;
    bool values_ = false;
    HeadShadowKey key_, drawnKey_;
    bool headStale_ = true;
    vk::Sampler compare_; // depth compare, bilinear (each PCF tap is itself a 2x2 filter)
    vk::Sampler nearest_; // the hair's first depth as a value
    vk::Sampler linear_;  // the opacity layers
    std::array<VkDescriptorImageInfo, 4> infos_{};
    void updateInfos();
};

// The light's depth maps: the head, then the hair.
class ShadowPass : public Pass {
public:
    ShadowPass(LightMaps& maps, MeshPass& meshes) : maps_(maps), meshes_(meshes) {}
    const char* name() const override { return "shadow"; }
    void declare(PassIo& io) override;
    void record(VkCommandBuffer cmd, FrameContext& frame) override;
    void setEnabled(bool enabled) { enabled_ = enabled; } // off: the maps are only cleared
    void setHair(LightHairDraw* hair) { hair_ = hair; }   // null: the head alone
    // Off: the hair's depth map is left alone (the compute path writes it).
    void setHairDepth(bool drawn) { hairDepth_ = drawn; }

private:
    LightMaps& maps_;
    MeshPass& meshes_;
    LightHairDraw* hair_ = nullptr;
    bool enabled_ = true;
    bool hairDepth_ = true;
};

// The hair's deep opacity layers.
class OpacityPass : public Pass {
public:
    explicit OpacityPass(LightMaps& maps) : maps_(maps) {}
    const char* name() const override { return "opacity"; }
    void declare(PassIo& io) override;
    void record(VkCommandBuffer cmd, FrameContext& frame) override;
    void setEnabled(bool enabled) { enabled_ = enabled; }
    void setHair(LightHairDraw* hair) { hair_ = hair; } // null: the layers are only cleared

private:
    LightMaps& maps_;
    LightHairDraw* hair_ = nullptr;
    bool enabled_ = true;
};

} // namespace wisp
