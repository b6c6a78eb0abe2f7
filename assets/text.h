// assets/text.h: text files as every reader of them reads them (OBJ, TressFX 2 text, head
// descriptions): one rule for padding (NUL bytes and white space after the last word are dropped, as
// some exporters pad a file), for NUL bytes inside the text (an error naming the line, the byte and
// the word), for line endings (LF, CRLF or a bare CR), for quoting a file's text in a message, and
// for decimal numbers and the range of coordinates the float math of Wisp handles.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace wisp {

// `data` without a leading UTF-8 byte order mark and without trailing padding (NULs and white
// space). Offsets into the result are offsets into the file plus bomBytes(data).
std::string_view textOf(std::string_view data);
size_t bomBytes(std::string_view data);

// Throws UserError "PATH:LINE: byte N is a NUL byte inside the text (in 'WORD')..." when `text`
// (textOf the file's data, `offset` bytes into the file) holds a NUL; `kind` names what the text
// should be ("OBJ text").
void checkNoNulBytes(std::string_view text, size_t offset, const std::filesystem::path& path, std::string_view kind);

// The lines of `text`, each ended by "\n", "\r\n" or "\r" (none has its ending).
std::vector<std::string_view> splitLines(std::string_view text);

// The 1-based line that byte `at` of `text` lies on, with splitLines' endings.
size_t lineOfByte(std::string_view text, size_t at);

// `text` as a message may quote it: control and non-ASCII bytes written \xNN, at most `limit`
// characters (then "...").
std::string quoteText(std::string_view text, size_t limit = 80);

// Reads a decimal number (as std::from_chars, a leading '+' allowed) into `out`. A number too
// small for a float reads as the float it rounds to (zero or a denormal: 1e-48 is 0). Returns an
// empty string, or why the word is no number a float holds ("'x' is not a number", "'1e39' is
// beyond the float range (+-3.4e38)", "'inf' is not a finite number").
std::string parseFloatWord(std::string_view word, float& out);

// The largest coordinate magnitude a head or a groom may have, in its file's units: past it the
// float math of placement, growth and the simulation (squared lengths, cross products, the
// fixed-point grid's scale) loses the hair. 1e9 is a head of a metre in nanometres.
inline constexpr double kMaxCoordinate = 1e9;

// Empty when |value| <= kMaxCoordinate, else the message: "coordinate 1e+30 is out of the range
// Wisp's float math handles (|x| <= 1e+09 in the file's units): scale the file down".
std::string coordinateRangeError(double value);

} // namespace wisp
