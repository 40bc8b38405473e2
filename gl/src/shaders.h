#pragma once
#include <string>

namespace svo::gl {

/// The text of an embedded shader file, with each `#include "name"` line
/// replaced by that embedded file's text. Throws svo::Error for an unknown name.
std::string shaderSource(const std::string& name);

} // namespace svo::gl
