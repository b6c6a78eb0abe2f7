// app/settings/value_text.cpp: numbers, ranges and JSON types as text (see value_text.h).
#include "app/settings/value_text.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace wisp {

double shortest(float f)
{
    char buffer[32];
    auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), f);
    return ec == std::errc() ? std::strtod(std::string(buffer, end).c_str(), nullptr) : double(f);
}

std::string numberText(double v)
{
    char buffer[40];
    if (v == std::floor(v) && std::abs(v) < 1e15) {
        std::snprintf(buffer, sizeof(buffer), "%.0f", v == 0.0 ? 0.0 : v);
        return buffer;
    }
    for (int precision = 1; precision <= 17; ++precision) {
        std::snprintf(buffer, sizeof(buffer), "%.*g", precision, v);
        if (std::strtod(buffer, nullptr) == v)
            break;
    }
    return buffer;
}

std::string rangeText(const Range& r, const std::string& unit)
{
    return numberText(r.min) + " .. " + numberText(r.max) + (unit.empty() ? "" : " " + unit);
}

std::string jsonTypeName(const nlohmann::ordered_json& v)
{
    switch (v.type()) {
    case nlohmann::ordered_json::value_t::object:
        return "an object";
    case nlohmann::ordered_json::value_t::array:
        return "an array";
    case nlohmann::ordered_json::value_t::string:
        return "a string";
    case nlohmann::ordered_json::value_t::boolean:
        return "true or false";
    case nlohmann::ordered_json::value_t::null:
        return "null";
    default:
        return "a number";
    }
}

} // namespace wisp
