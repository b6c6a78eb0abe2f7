// fuzz/fuzz_tfx2.cpp: libFuzzer target of the TressFX 2 text reader: the input is the whole file
// (the seeds start with header keys, so the format detection sends most inputs to the reader).
#include "fuzz_support.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    std::string bytes(reinterpret_cast<const char*>(data), size);
    wisp::fuzz::run([&] { return wisp::parseHairAsset(bytes, "fuzz.tfx"); }, wisp::fuzz::checkHair);
    return 0;
}
