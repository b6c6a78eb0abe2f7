// gpu/timestamps.h: GPU timestamps around named scopes (one per pass), read back once the
// frame's fence has signalled, converted to milliseconds with timestampPeriod and masked to
// timestampValidBits.
#pragma once

#include "gpu/handle.h"

#include <algorithm>
#include <string>
#include <vector>

namespace wisp::vk {

class Context;

struct ScopeTime {
    std::string name;
    double milliseconds = 0.0;
};

// A frame's scopes with those of one name added up, in the order their names first appear (the
// physics' kernels recorded beside several passes time as one `physics`).
inline std::vector<ScopeTime> timingsByName(const std::vector<ScopeTime>& scopes)
{
    std::vector<ScopeTime> out;
    for (const ScopeTime& s : scopes) {
        auto same = std::find_if(out.begin(), out.end(), [&](const ScopeTime& o) { return o.name == s.name; });
        if (same != out.end())
            same->milliseconds += s.milliseconds;
        else
            out.push_back(s);
    }
    return out;
}

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
