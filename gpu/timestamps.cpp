// gpu/timestamps.cpp: a query pool of 2 timestamps per scope.
#include "gpu/timestamps.h"

#include "gpu/check.h"
#include "gpu/context.h"

#include <stdexcept>

namespace wisp::vk {

GpuTimer::GpuTimer(const Context& ctx, uint32_t maxScopes, const char* name)
    : device_(ctx.device()), capacity_(maxScopes), periodNs_(ctx.report().timestampPeriodNs)
{
    uint32_t bits = ctx.report().timestampValidBits;
    validMask_ = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
    VkQueryPoolCreateInfo info{.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
                               .queryType = VK_QUERY_TYPE_TIMESTAMP,
                               .queryCount = 2 * maxScopes};
    VkQueryPool pool = VK_NULL_HANDLE;
    VK_CHECK(vkCreateQueryPool(device_, &info, nullptr, &pool));
    ctx.setName(pool, VK_OBJECT_TYPE_QUERY_POOL, name);
    pool_ = QueryPool(device_, pool);
}

void GpuTimer::reset(VkCommandBuffer cmd)
{
    vkCmdResetQueryPool(cmd, pool_, 0, 2 * capacity_);
    names_.clear();
    open_ = UINT32_MAX;
}

void GpuTimer::begin(VkCommandBuffer cmd, const std::string& scope)
{
    if (open_ != UINT32_MAX)
        throw std::logic_error("GpuTimer: scope '" + scope + "' begun inside '" + names_[open_] + "'");
    if (names_.size() >= capacity_)
        throw std::logic_error("GpuTimer: more than " + std::to_string(capacity_) + " scopes in a frame");
    open_ = static_cast<uint32_t>(names_.size());
    names_.push_back(scope);
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, pool_, 2 * open_);
}

void GpuTimer::end(VkCommandBuffer cmd)
{
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, pool_, 2 * open_ + 1);
    open_ = UINT32_MAX;
}

std::vector<ScopeTime> GpuTimer::read() const
{
    std::vector<ScopeTime> out;
    if (names_.empty())
        return out;
    std::vector<uint64_t> ticks(2 * names_.size());
    VK_CHECK(vkGetQueryPoolResults(device_, pool_, 0, static_cast<uint32_t>(ticks.size()),
                                   ticks.size() * sizeof(uint64_t), ticks.data(), sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    for (size_t i = 0; i < names_.size(); ++i) {
        uint64_t delta = ((ticks[2 * i + 1] & validMask_) - (ticks[2 * i] & validMask_)) & validMask_;
        out.push_back({names_[i], static_cast<double>(delta) * periodNs_ * 1e-6});
    }
    return out;
}

} // namespace wisp::vk
