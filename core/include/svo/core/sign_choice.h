#pragma once
/// @file sign_choice.h
/// @brief Which sign method a level set or solid uses, and why: one rule for
/// the GPU and CPU paths (svo/gl/field_pipeline.h).
#include <string>
#include <vector>

#include "svo/core/field_options.h"
#include "svo/core/mesh.h"

namespace svo {

/// The sign method a call uses, and why (for the statistics).
struct SignChoice {
    SignMethod method = SignMethod::Parity;
    std::string why; ///< e.g. "parity: the mesh is closed and ...", "winding: as asked"
};

/// @brief Resolves SignMethod::Auto and checks an explicit choice against the mesh.
/// @details Auto takes parity for a closed, consistently oriented mesh (after
/// welding vertices at equal positions) and the winding number otherwise.
/// Parity asked for a mesh with holes is refused; for one that is otherwise
/// not closed (edges of three or more triangles, flipped faces) it is kept
/// with a warning. SignOptions::partOfClosedMesh takes parity unchecked.
/// @param mesh     the mesh (its source names it in messages)
/// @param asked    the sign options of the call
/// @param warnings receives the warning for parity asked on a mesh that is not closed
/// @return the method and why
/// @throw svo::InvalidInput for a winding accuracy that fails
///        checkWindingAccuracy, parity asked on a mesh with holes, or winding
///        numbers asked for a part of a closed mesh.
SignChoice chooseSign(const TriangleMesh& mesh, const SignOptions& asked, std::vector<std::string>& warnings);

} // namespace svo
