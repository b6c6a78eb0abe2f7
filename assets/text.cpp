// assets/text.cpp: the text rules every text reader shares (assets/text.h): padding, NUL bytes,
// line endings, quoting, numbers and the coordinate range.
#include "assets/text.h"

#include "core/error.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace wisp {

size_t bomBytes(std::string_view data)
{
    return data.starts_with("\xEF\xBB\xBF") ? 3 : 0;
}

std::string_view textOf(std::string_view data)
{
    data.remove_prefix(bomBytes(data));
    size_t last = data.find_last_not_of(std::string_view(" \t\r\n\v\f\0", 7));
    return data.substr(0, last == std::string_view::npos ? 0 : last + 1);
}

size_t lineOfByte(std::string_view text, size_t at)
{
    size_t line = 1;
    for (size_t k = 0; k < at && k < text.size(); ++k)
        if (text[k] == '\n' || (text[k] == '\r' && (k + 1 >= text.size() || text[k + 1] != '\n')))
            ++line;
    return line;
}

std::vector<std::string_view> splitLines(std::string_view text)
{
    std::vector<std::string_view> lines;
    while (!text.empty()) {
        size_t end = text.find_first_of("\r\n");
        lines.push_back(text.substr(0, end));
        if (end == std::string_view::npos)
            break;
        size_t next = end + (text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n' ? 2 : 1);
        text.remove_prefix(next);
    }
    return lines;
}

std::string quoteText(std::string_view text, size_t limit)
{
    std::string out;
    for (char c : text) {
        if (out.size() >= limit) {
            out += "...";
            break;
        }
        unsigned char u = static_cast<unsigned char>(c);
        if (u >= 0x20 && u < 0x7f) {
            out.push_back(c);
        } else {
            char hex[8];
            std::snprintf(hex, sizeof(hex), "\\x%02X", unsigned(u));
            out += hex;
        }
    }
    return out;
}

void checkNoNulBytes(std::string_view text, size_t offset, const std::filesystem::path& path, std::string_view kind)
{
    size_t nul = text.find('\0');
    if (nul == std::string_view::npos)
        return;
    // The word holding it: the run of bytes around it up to white space.
    size_t start = text.find_last_of(" \t\r\n", nul);
    start = start == std::string_view::npos ? 0 : start + 1;
    size_t end = std::min(text.find_first_of(" \t\r\n", nul), text.size());
    throw UserError(path.string() + ":" + std::to_string(lineOfByte(text, nul)) + ": byte " +
                    std::to_string(offset + nul) + " is a NUL byte inside the text (in '" +
                    quoteText(text.substr(start, end - start), 40) + "'): " + std::string(kind) +
                    " holds none but as padding at the end of the file (binary data?)");
}

namespace {

// The decimal order of magnitude of a number std::from_chars matched whole (digits, an optional
// point and exponent): negative when it is below 1. Only its sign is used, to tell a number too
// small for a double from one too large.
long decimalOrder(std::string_view word)
{
    size_t k = word.starts_with('-') ? 1 : 0;
    long order = 0;
    bool nonzero = false;
    for (; k < word.size() && word[k] >= '0' && word[k] <= '9'; ++k) {
        nonzero = nonzero || word[k] != '0';
        order += nonzero ? 1 : 0;
    }
    if (!nonzero && k < word.size() && word[k] == '.')
        for (++k; k < word.size() && word[k] == '0'; ++k)
            --order;
    size_t e = word.find_first_of("eE");
    long exponent = 0;
    if (e != std::string_view::npos) {
        std::string_view digits = word.substr(e + 1);
        if (digits.starts_with('+'))
            digits.remove_prefix(1);
        auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), exponent);
        if (ec == std::errc::result_out_of_range)
            exponent = digits.starts_with('-') ? -1000000 : 1000000;
    }
    return order + exponent;
}

} // namespace

std::string parseFloatWord(std::string_view word, float& out)
{
    std::string_view digits = word.starts_with('+') ? word.substr(1) : word;
    const char* first = digits.data();
    const char* last = first + digits.size();
    auto [end, ec] = std::from_chars(first, last, out);
    if (end != last || (ec != std::errc() && ec != std::errc::result_out_of_range))
        return "'" + quoteText(word, 40) + "' is not a number";
    if (ec == std::errc::result_out_of_range) {
        // Too small for a float (it rounds to zero or to a denormal) or too large for one.
        double d = 0.0;
        auto [dend, dec] = std::from_chars(first, last, d);
        bool tiny = dec == std::errc() ? std::abs(d) < 1.0 : decimalOrder(digits) < 0;
        if (!tiny)
            return "'" + quoteText(word, 40) + "' is beyond the float range (+-3.4e38)";
        out = dec == std::errc() ? static_cast<float>(d) : 0.0f;
        if (out == 0.0f && digits.starts_with('-'))
            out = -0.0f;
        return {};
    }
    if (!std::isfinite(out))
        return "'" + quoteText(word, 40) + "' is not a finite number";
    return {};
}

std::string coordinateRangeError(double value)
{
    if (std::abs(value) <= kMaxCoordinate)
        return {};
    char text[96];
    std::snprintf(text, sizeof(text), "coordinate %.3g is out of the range Wisp's float math handles (|x| <= %.0e",
                  value, kMaxCoordinate);
    return std::string(text) + " in the file's units): scale it down";
}

} // namespace wisp
