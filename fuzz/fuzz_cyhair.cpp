// fuzz/fuzz_cyhair.cpp: libFuzzer target of the cyHair reader: the input is the file after its
// "HAIR" magic, so every input reaches the reader.
#include "fuzz_support.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    std::string bytes = "HAIR" + std::string(reinterpret_cast<const char*>(data), size);
    wisp::fuzz::run([&] { return wisp::parseHairAsset(bytes, "fuzz.hair"); }, wisp::fuzz::checkHair);
    return 0;
}
