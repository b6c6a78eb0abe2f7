// fuzz/fuzz_support.h: what the fuzz targets share. A loader or the scene parser may refuse an
// input with a UserError (that is a fine outcome); anything else it throws, and any result that
// breaks the promises the rest of Wisp relies on, aborts so libFuzzer reports it as a crash. The
// hair and mesh contracts live here; the scene's in fuzz_scene.cpp.
#pragma once

#include "assets/hair_asset.h"
#include "assets/mesh.h"
#include "core/error.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

namespace wisp::fuzz {

[[noreturn]] inline void broken(const std::string& what)
{
    std::fprintf(stderr, "fuzz: the result breaks its contract: %s\n", what.c_str());
    std::abort();
}

inline bool finite(glm::vec3 p)
{
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

// A loaded hair asset: at least one strand, every strand at least 2 finite points, a pinned
// root count of at least 1.
inline void checkHair(const HairAsset& asset)
{
    if (asset.strands.empty())
        broken("no strands");
    for (size_t s = 0; s < asset.strands.size(); ++s) {
        const HairStrand& strand = asset.strands[s];
        if (strand.points.size() < 2)
            broken("strand " + std::to_string(s) + " has " + std::to_string(strand.points.size()) + " points");
        if (strand.pinnedRoot < 1)
            broken("strand " + std::to_string(s) + " pins no root");
        for (const glm::vec3& p : strand.points)
            if (!finite(p))
                broken("strand " + std::to_string(s) + " has a non-finite point");
    }
}

// A loaded mesh: as many unit normals as positions, whole triangles, every index in range,
// finite positions.
inline void checkMesh(const Mesh& mesh)
{
    if (mesh.normals.size() != mesh.positions.size())
        broken("normals and positions differ in count");
    if (mesh.indices.size() % 3 != 0)
        broken("indices are not whole triangles");
    for (uint32_t i : mesh.indices)
        if (i >= mesh.positions.size())
            broken("index " + std::to_string(i) + " past " + std::to_string(mesh.positions.size()) + " positions");
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        if (!finite(mesh.positions[v]))
            broken("position " + std::to_string(v) + " is not finite");
        float len = glm::length(mesh.normals[v]);
        if (!(std::abs(len - 1.0f) < 1e-3f))
            broken("normal " + std::to_string(v) + " has length " + std::to_string(len));
    }
}

// Runs `load` and checks its result with `check`; a UserError ends the input quietly.
template <typename Load, typename Check> void run(Load&& load, Check&& check)
{
    try {
        check(load());
    } catch (const UserError&) {
    }
}

} // namespace wisp::fuzz
