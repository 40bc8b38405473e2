#pragma once
// What every mesh-reader fuzz target asserts: any bytes through the reader and
// mesh validation give a mesh whose indices are in range (and colours, if
// any, one per vertex), or svo::Error; anything else aborts. The text readers
// also read the bytes in pieces of a few bytes, as they read large files in
// parallel: the same mesh or the same error, or it aborts (sameInPieces).
#include <cstdint>
#include <cstdlib>
#include <string>

#include "svo/core/error.h"
#include "svo/core/mesh.h"
#include "one_thread.h"

template <typename Read>
int fuzzMeshReader(const uint8_t* data, size_t size, Read read)
{
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    try {
        const svo::TriangleMesh mesh = read(bytes);
        svo::validateMesh(mesh);
        for (const auto& t : mesh.triangles)
            for (uint32_t v : t)
                if (v >= mesh.positions.size()) std::abort(); // validation let a bad index through
        if (!mesh.colors.empty() && mesh.colors.size() != mesh.positions.size()) std::abort();
    } catch (const svo::Error&) {
    }
    return 0;
}

/// The mesh or the error message a read gives, for comparing two reads.
template <typename Read>
std::string outcomeOf(Read&& read, const std::string& bytes, svo::TriangleMesh& mesh)
{
    try {
        mesh = read(bytes);
        return "";
    } catch (const svo::Error& e) {
        return e.what();
    }
}

/// Aborts unless reading `bytes` as one piece and in pieces give the same.
template <typename Whole, typename Pieces>
void sameInPieces(const uint8_t* data, size_t size, Whole whole, Pieces pieces)
{
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    svo::TriangleMesh a, b;
    if (outcomeOf(whole, bytes, a) != outcomeOf(pieces, bytes, b)) std::abort();
    if (a.triangles != b.triangles || a.positions.size() != b.positions.size() || a.colors.size() != b.colors.size() ||
        a.warnings != b.warnings)
        std::abort();
    for (size_t i = 0; i < a.positions.size(); ++i)
        for (int k = 0; k < 3; ++k)
            if (!(a.positions[i][k] == b.positions[i][k])) std::abort();
    for (size_t i = 0; i < a.colors.size(); ++i)
        for (int k = 0; k < 3; ++k)
            if (!(a.colors[i][k] == b.colors[i][k])) std::abort();
}
