/* view_layout.h: the viewer's and the lighting volume's binding slots, image and texture units.

   C++ and GLSL at once, on top of gpu_layout.h and under its rules (see
   there). Shaders include "gpu_layout.h" and then this file. */
#ifndef SVO_VIEW_LAYOUT_H
#define SVO_VIEW_LAYOUT_H

#ifdef __cplusplus
#include <cstddef>
#include <svo/core/gpu_layout.h>
namespace svo::gpu {
#endif

/* Viewer (gl/view/src/octree_view.cpp, view_*.vert/frag/comp): the octree's
   buffers as uploaded for drawing, and each node's origin in voxels. */
#define SVO_BIND_VIEW_NODES 0
#define SVO_BIND_VIEW_BRICKS 1
#define SVO_BIND_VIEW_ORIGINS 2 /* uvec4 per node: local origin (voxels), unused */
#define SVO_BIND_VIEW_VOXEL_START 3 /* uint per brick: its first voxel in voxel order */
#define SVO_BIND_VIEW_ATTRIBUTE 4   /* the coloured channel, voxel order: 3 floats (normal, colour) or 1 uint (triangle) */
#define SVO_BIND_VIEW_OPACITY 5     /* 2 floats per node, AO mip-map: min(1, voxels / face voxels); that or the most opaque child's */
#define SVO_BIND_VIEW_LIGHTS 6      /* lighting: 2 vec4 per light, cell space (light_volume.glsl) */
#define SVO_BIND_VIEW_NORMALS 7     /* lighting: the normal channel, 3 floats per voxel, voxel order */
#define SVO_BIND_VIEW_ALBEDO 8      /* lighting: the colour channel, 3 floats per voxel (or unused) */
#define SVO_BIND_VIEW_DIRECT 9      /* lighting: per voxel, the irradiance on its normal's side and on the other, packed halves (view_lights.glsl) */
#define SVO_BIND_VIEW_LOOP_CUT 10   /* uint: invocations whose loops a CPU rasterizer cut short (loop_cut.glsl) */
/* Lighting volume (gl/view/src/light_volume.cpp): texture and image units. */
#define SVO_UNIT_LIGHT_OPACITY 0  /* texture: rgb = opacity seen along x, y, z */
#define SVO_UNIT_LIGHT_RADIANCE 1 /* texture: rgb = radiance x coverage, a = coverage */
#define SVO_UNIT_LIGHT_ALONG 2 /* textures 2..7: radiance seen along +x -x +y -y +z -z, levels 1.. */
#define SVO_UNIT_LIGHT_LIT_SIDE 8 /* texture: level 0's lit side times its light (rgba16f) */
#define SVO_UNIT_LIGHT_CLEAR 11   /* texture: per texel of level 0, the coarsest level clear of voxels (r8ui) */
/* Viewer: the voxel pass's pixels, written as an image by view_voxels.comp
   and read as a texture by view_pixels.frag. GL promises 8 image units. */
#define SVO_IMAGE_VIEW_PIXELS 0
#define SVO_UNIT_VIEW_PIXELS 9
/* Viewer, interleaved cones: each pixel's gathered light, albedo and normal
   (rgba32ui) and the point its cones left from (rgba32f), written by
   view_voxels.comp and averaged by view_resolve.comp. */
#define SVO_IMAGE_VIEW_GATHER 1
#define SVO_IMAGE_VIEW_POINTS 2
/* Viewer, ViewLayers::surface = Mesh: the mesh rasterized into the triangle
   each pixel sees (its index + 1; 0 where none covers the pixel), read by
   view_voxels.comp with the mesh's positions (3 floats a vertex, cell
   space) and triangles (3 uints), where each pixel's ray meets it. */
#define SVO_UNIT_VIEW_SURFACE_TRIANGLE 10
#define SVO_BIND_VIEW_MESH_POSITIONS 11
#define SVO_BIND_VIEW_MESH_TRIANGLES 12
/* ViewLayers::voxelColor as the shader reads it. */
#define SVO_VIEW_COLOR_FLAT 0
#define SVO_VIEW_COLOR_NORMAL 1
#define SVO_VIEW_COLOR_RGB 2
#define SVO_VIEW_COLOR_TRIANGLE 3

#ifdef __cplusplus
static_assert(distinctSlots({SVO_IMAGE_VIEW_PIXELS, SVO_IMAGE_VIEW_GATHER, SVO_IMAGE_VIEW_POINTS}));
static_assert(distinctSlots({SVO_UNIT_LIGHT_OPACITY, SVO_UNIT_LIGHT_RADIANCE, SVO_UNIT_LIGHT_ALONG,
                             SVO_UNIT_LIGHT_ALONG + 1, SVO_UNIT_LIGHT_ALONG + 2, SVO_UNIT_LIGHT_ALONG + 3,
                             SVO_UNIT_LIGHT_ALONG + 4, SVO_UNIT_LIGHT_ALONG + 5, SVO_UNIT_LIGHT_LIT_SIDE, SVO_UNIT_VIEW_PIXELS,
                             SVO_UNIT_VIEW_SURFACE_TRIANGLE, SVO_UNIT_LIGHT_CLEAR}));
static_assert(distinctSlots({SVO_BIND_VIEW_NODES, SVO_BIND_VIEW_BRICKS, SVO_BIND_VIEW_ORIGINS,
                             SVO_BIND_VIEW_VOXEL_START, SVO_BIND_VIEW_ATTRIBUTE, SVO_BIND_VIEW_OPACITY,
                             SVO_BIND_VIEW_LIGHTS, SVO_BIND_VIEW_NORMALS, SVO_BIND_VIEW_ALBEDO,
                             SVO_BIND_VIEW_DIRECT, SVO_BIND_VIEW_LOOP_CUT, SVO_BIND_VIEW_MESH_POSITIONS,
                             SVO_BIND_VIEW_MESH_TRIANGLES}));
} // namespace svo::gpu
#endif

#endif /* SVO_VIEW_LAYOUT_H */
