// The terrain as the real-time view draws it (renders/view/ldi_renderer.cpp, step 7): the scene's
// mesh cut into a square grid of chunks, each with levels of detail. Internal to renders/view.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "templates/mesh.h"

namespace wangscape {

// About this many of the mesh's triangles per chunk (the chunks are a square grid over the mesh's
// extent, so where the mesh is finer, as under the field, a chunk holds more).
inline constexpr std::size_t kTerrainChunkTriangles = 1024;

// The terrain mesh in a square grid of chunks, each with its own copy of its vertices
// (contiguous), so a frame culls whole chunks by their box and transforms only the vertices of
// those it draws, with no two tasks writing one vertex. Each chunk has levels of detail: level 0,
// the mesh's own triangles whose centroid lies in the chunk's square; then regular grids of
// 2 n x n triangles over the square (n halving down to 1) whose vertices are the fine mesh's
// surface and light sampled at the grid's points (where a grid cell leaves the mesh, at its outer
// border, the cell keeps the fine triangles). A level's error bounds how far it strays from the
// fine mesh: vertically, or by its cell's size where its light strays (a shadow's edge moved
// by up to a cell). A frame takes the coarsest level whose error projects under the renderer's
// terrain error (LdiRenderer::set_terrain_error, in pixels). Skirts hang from a grid's edges, so that no crack opens
// between chunks of different levels; how deep is decided per frame, from the levels drawn around
// (Level::height_error).
struct TerrainChunks {                                  // structure of arrays
  std::vector<float> x, y, z;                           // ENU meters (a skirt's bottom: its top)
  std::vector<float> light_r, light_g, light_b;         // sun + sky irradiance (linear) at the vertex
  std::vector<std::array<std::uint32_t, 3>> triangles;  // chunk by chunk, level by level
  struct Level {
    std::uint32_t first_vertex = 0, vertex_count = 0, first_triangle = 0, triangle_count = 0;
    std::uint32_t skirt_vertices = 0;   // the level's last vertices: skirts' bottoms (z: their top)
    std::uint32_t skirt_triangles = 0;  // the level's last triangles: skirts (seen from both sides)
    float error = 0;                    // meters: vertical, or the cell's size where the light strays
    float height_error = 0;             // meters: vertical only (what a skirt must bridge)
  };
  // A fine triangle owned by a neighbouring chunk (its centroid there) that reaches into this
  // chunk's square: drawn with this chunk's level 0 while its owner is drawn coarser (a grid
  // covers only its own square).
  struct Borrowed {
    std::array<std::uint32_t, 3> ids;  // into this chunk's level-0 vertices
    std::uint32_t owner;               // chunk index
  };
  struct Chunk {
    std::uint32_t first_level = 0, level_count = 0;  // into levels; the first is the fine mesh
    std::uint32_t first_borrowed = 0, borrowed_count = 0;
    std::array<std::int32_t, 4> neighbours{-1, -1, -1, -1};  // chunks west, east, south, north (-1: none)
    std::array<float, 3> low{}, high{};  // the box of its levels' vertices (skirts' tops), ENU meters
  };
  std::vector<Chunk> chunks;
  std::vector<Level> levels;
  std::vector<Borrowed> borrowed;
};

// The chunks and their levels of `mesh` (ENU meters), with `light` per vertex of the mesh.
TerrainChunks make_terrain_chunks(const Mesh& mesh, const std::vector<std::array<float, 3>>& light);

}  // namespace wangscape
