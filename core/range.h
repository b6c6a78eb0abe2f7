// core/range.h: a closed numeric range, the one type every setting's limits are written in.
#pragma once

namespace wisp {

struct Range {
    double min;
    double max;
    constexpr bool contains(double v) const { return v >= min && v <= max; }
};

} // namespace wisp
