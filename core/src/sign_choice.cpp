// The sign method of a level set or solid (svo/core/sign_choice.h).
#include "svo/core/sign_choice.h"

#include <fmt/format.h>

#include "svo/core/error.h"
#include "svo/core/mesh_topology.h"

namespace svo {

SignChoice chooseSign(const TriangleMesh& mesh, const SignOptions& asked, std::vector<std::string>& warnings)
{
    checkWindingAccuracy(asked.windingAccuracy, "SignOptions::windingAccuracy");
    if (asked.partOfClosedMesh) {
        // The caller vouches for the whole mesh; the part is open where it was cut.
        if (asked.method == SignMethod::Winding)
            throw InvalidInput(std::vector<Error::Part>{Error::option("SignOptions::partOfClosedMesh"), " with ",
                                                        Error::option("SignOptions::method"),
                                " winding: a part of a closed mesh takes parity signs (winding numbers sum over the "
                                "whole mesh)"});
        return {SignMethod::Parity, "parity: a part of a closed mesh, as the caller says"};
    }
    if (asked.method == SignMethod::Winding) return {SignMethod::Winding, "winding: as asked"};
    const EdgeReport edges = checkEdges(mesh);
    if (edges.closedAndOriented()) return {SignMethod::Parity, "parity: the mesh is " + edges.describe()};
    if (asked.method == SignMethod::Auto)
        return {SignMethod::Winding, "winding: the mesh is not closed (" + edges.describe() + ")"};
    // An option the mesh cannot take (InvalidInput: asked differently, it works).
    // A hole lets a column of voxel centres cross the surface an odd number
    // of times, and parity then flips every sign beyond it: refused. Edges of
    // three or more triangles, or two running the same way, can still give
    // even crossings (two solids sharing an edge, a flipped face): warned.
    if (edges.boundary)
        throw InvalidInput(fmt::format("{}: parity signs need a mesh without holes, and this one has {}: a column of voxels "
                                "through a hole crosses the surface an odd number of times and every sign beyond it "
                                "would flip; use the winding sign method (or auto, which picks it for such a mesh)",
                                mesh.source, edges.describe()));
    warnings.push_back(fmt::format("{} is not closed ({}): parity signs may be wrong", mesh.source, edges.describe()));
    return {SignMethod::Parity, "parity: as asked (the mesh is not closed)"};
}

} // namespace svo
