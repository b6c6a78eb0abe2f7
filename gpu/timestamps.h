// gpu/timestamps.h: GPU timestamps around named scopes (one per pass), read back once the
// frame's fence has signalled, converted to milliseconds with timestampPeriod and masked to
// timestampValidBits.
#pragma once

#include "gpu/handle.h"

#include <string>
#include <vector>

namespace wisp::vk {

class Context;

struct ScopeTime {
    std::string name;
    double milliseconds = 0.0;
};

class GpuTimer {
public:
    GpuTimer() = default;
    GpuTimer(const Context& ctx, uint32_t maxScopes, const char* name);

    void reset(VkCommandBuffer cmd); // at the start of the frame's command buffer
    void begin(VkCommandBuffer cmd, const std::string& scope);
    void end(VkCommandBuffer cmd);
    // The scopes of the last frame recorded into this timer; call after its fence signalled.
    std::vector<ScopeTime> read() const;

private:
    VkDevice device_ = VK_NULL_HANDLE;
    QueryPool pool_;
    uint32_t capacity_ = 0;
    uint64_t validMask_ = 0;
    double periodNs_ = 1.0;
    std::vector<std::string> names_;
    uint32_t open_ = UINT32_MAX;
};

} // namespace wisp::vk
