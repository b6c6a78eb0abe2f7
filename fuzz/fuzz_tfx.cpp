// fuzz/fuzz_tfx.cpp: libFuzzer target of the TressFX 3 and 4 binary readers. The first input byte
// picks the version (odd: 4.0, even: 3.0), written as the file's leading float; the rest of the
// input is the file from byte 4 on. So every input reaches one of the two readers.
#include "fuzz_support.h"

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    if (size == 0)
        return 0;
    uint32_t version = std::bit_cast<uint32_t>((data[0] & 1u) ? 4.0f : 3.0f);
    std::string bytes(4, '\0');
    for (int k = 0; k < 4; ++k)
        bytes[size_t(k)] = char((version >> (8 * k)) & 0xffu); // little-endian, as the files are
    bytes.append(reinterpret_cast<const char*>(data) + 1, size - 1);
    wisp::fuzz::run([&] { return wisp::parseHairAsset(bytes, "fuzz.tfx"); }, wisp::fuzz::checkHair);
    return 0;
}
