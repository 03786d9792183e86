// Cube maps in memory (docs/cube-maps.md): each face's levels stored with a one-texel skirt around
// them holding the neighbouring faces' edge texels, and at the four skirt corners the average of
// the three texels that meet at the cube's corner (Vulkan's seamless rule). A bilinear footprint
// anywhere on a face then lies inside its skirted face: the seams cost memory ((n + 2)^2 / n^2 per
// level), not logic, and the parity banks keep one sample per clock across them.
#pragma once
#include <vector>

#include "pyramid.h"

namespace tex {

// The skirted faces of cubes: `faces` holds 6 per cube (+X, -X, +Y, -Y, +Z, -Z), square, of one
// size, format and level count; the result the same count of pyramids whose level k is
// (n_k + 2) x (n_k + 2): the face at (1..n_k, 1..n_k), skirt texel (0, j + 1) the texel that
// adjoins the face's texel (0, j) across its left edge on the neighbouring face (likewise the other
// edges), each skirt corner round((a + b + c) / 3) of the face's corner texel and the two that
// adjoin it. An sRGB cube averages its codes, then decodes them (`levels` linear, `codes` stored).
// Throws tex::Error for a count that is not a multiple of 6, faces that are not square or differ,
// or a block format (a skirt would need its blocks encoded again).
std::vector<Pyramid> cube_skirts(const std::vector<const Pyramid*>& faces);

// Where the texel adjoining texel (x, y) of `face` (n x n, x or y one step outside 0..n-1 on one
// side only) lies: the neighbouring face and its texel. By the face table itself: the direction of
// the outside texel's centre selects the neighbour (stage::cube_face's table in doubles).
struct CubeTexel {
  int face = 0, x = 0, y = 0;
};
CubeTexel cube_neighbour(int face, int x, int y, int n);

}  // namespace tex
