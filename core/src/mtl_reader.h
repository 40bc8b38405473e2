#pragma once
/// @file mtl_reader.h (internal)
/// OBJ material libraries (.mtl): the diffuse colour (Kd) of each material,
/// which svo uses as the colour of an OBJ's faces that have no vertex colours.
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "svo/core/vec3.h"

namespace svo::detail {

/// Each material a .mtl file defines (`newmtl name`) and its diffuse colour:
/// `Kd r g b` (or `Kd r`, grey), nullopt for a material without Kd or with a
/// spectral or CIE XYZ one (`Kd spectral`, `Kd xyz`), which have no RGB here.
/// Other statements are ignored; a later definition of a name replaces an
/// earlier one. Throws svo::IoError naming `path` and the line for a Kd
/// outside a material or with a malformed or non-finite number.
std::map<std::string, std::optional<Vec3f>> readMtl(const std::string& path, std::string_view bytes);

/// The rest of a statement after its keyword, blanks trimmed (a material or
/// file name, which may hold spaces).
std::string_view statementArgument(std::string_view line, std::string_view keyword);

} // namespace svo::detail
