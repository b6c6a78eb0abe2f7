// fuzz/fuzz_obj.cpp: libFuzzer target of the OBJ reader (the line-by-line check, then
// tinyobjloader, then Wisp's vertex and normal assembly): the input is the whole file.
#include "fuzz_support.h"

#include <cstddef>
#include <cstdint>
#include <sstream>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
    wisp::fuzz::run([&] { return wisp::parseObj(in, "fuzz.obj"); }, wisp::fuzz::checkMesh);
    return 0;
}
