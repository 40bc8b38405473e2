#pragma once
/// @file view_window.h
/// svo view's window: GLFW with an OpenGL 4.5 core context, the library's
/// OctreeView drawing into it (the svo Context adopts the window's), and a
/// Dear ImGui panel. Mesh inputs are re-voxelized live on the GPU.
#include <string>

#include "cli_options.h"
#include "svo/gl/octree_view.h"
#include "svo/gl/view_request.h"
#include "svo/load_octree.h"
#include "svo/vdb_io/octree_files.h"
#include "svo/voxelizer.h"

namespace svo::app {

struct ViewWindowInput {
    std::string title;        ///< the input's name
    LoadedOctree loaded;      ///< the first octree, and the mesh when the input is one
    VoxelizeStats stats;      ///< what building it measured
    int64_t resolution = 256; ///< of the first octree: live re-voxelization starts here
    BackendArgs backend;      ///< backend, dilation and mode for re-voxelization
    gl::ViewCamera camera;    ///< the first camera
    gl::ViewLayers layers;
    /// --surface auto: the mesh's surface while AO alone or lighting is on
    /// (when the input is a mesh), else the voxels; the panel's checkbox ends it.
    bool autoSurface = false;
    bool room = false;        ///< lighting turned on without lights gets a room's (gl::ViewRequest::room)
    int width = 1280, height = 960; ///< the window's first size
    int frames = 0;           ///< close after this many frames; 0: when the user closes it
    std::string keys;         ///< pressed one per frame from the second frame on (scripted demos, tests)
    std::string save;         ///< write the octree shown last here on exit (.svo, .vdb, .nvdb)
};

/// What the window showed last, for the summary.
struct ViewWindowResult {
    Octree octree;
    int64_t resolution = 0;
    int frames = 0;
    double meanFrameMs = 0;   ///< wall time between frames
    std::string renderer;
    std::vector<std::string> screenshots;
    std::vector<std::string> errors; ///< re-voxelizations refused (the previous octree stayed)
};

/// Opens the window and runs it until it is closed (Esc, Q, the close
/// button) or `frames` have been drawn. Throws svo::Error in one line when no
/// window can be opened (no display, no OpenGL 4.5 core through GLX).
ViewWindowResult runViewWindow(ViewWindowInput input, Voxelizer& voxelizer);

} // namespace svo::app
