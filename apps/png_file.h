#pragma once
/// @file png_file.h
/// PNG output for pictures (libpng), written atomically like every svo output.
#include <string>

#include "svo/gl/octree_view.h"

namespace svo::app {

/// Writes an RGBA8 image (rows from the top) as an 8-bit RGB PNG, through a
/// temporary file and a rename. Throws svo::Error naming the path on failure.
void writePng(const std::string& path, const gl::Image& image);

} // namespace svo::app
