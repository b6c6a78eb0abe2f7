// app/settings/value_text.h: how values are written into messages and files, one way for the settings
// table, scene files and every message that names a value or a range: numbers as the shortest text
// that reads back as them ("0.3", "2000000"), ranges as "MIN .. MAX UNIT", JSON values by their
// type's name ("a string", "true or false").
#pragma once

#include "core/range.h"

#include <nlohmann/json.hpp>

#include <string>

namespace wisp {

// A float as the double of its shortest decimal (0.3f is 0.3, not 0.30000001192092896).
double shortest(float f);
// A double as the shortest text that reads back as it; whole numbers below 1e15 in full (2000000,
// not 2e+06).
std::string numberText(double v);
// "0.01 .. 2 m", "1 .. 4096".
std::string rangeText(const Range& r, const std::string& unit);
// "an object", "an array", "a string", "true or false", "null", "a number".
std::string jsonTypeName(const nlohmann::ordered_json& v);

} // namespace wisp
