// Automatic contact penalty (issue 16, part 3b): a scale-free default for eps_N and eps_T when a
// contact pair omits them, from the stiffness of the elements adjacent to its surfaces.
//   eps = eps_scale * kAutomaticPenaltyFactor * min(S_master, S_slave),
//   S = mean over the surface's faces of E/h of the element behind the face,
// with h twice the distance, along the face normal, from the face centre to the element's
// centre (the element's thickness normal to the face for a box). E/h is the stiffness per unit
// area of that element layer under a normal pressure; the softer side governs how much the
// penalty penetration adds to the elastic deflection of the contact zone, and the factor 10
// makes the penetration about a tenth of the element layer's own compression.
#pragma once

#include <string>
#include <vector>

#include "mesh/mesh.hpp"

namespace cc {

// The factor on E/h. On paper example 6.1 (E = 2.1e4, block elements 1 thick) it gives
// eps = 2.1e5, the paper's own choice for 6.1(b).
inline constexpr double kAutomaticPenaltyFactor = 10.0;

// The element layer behind a surface, both means over the same faces.
struct SurfaceLayer {
  double stiffness;  // mean E/h
  double depth;      // mean h: the depth of the element layer behind the surface
};

// The layer behind `faces`, in one pass over them; blockYoung[b] is Young's modulus of mesh block
// b (NaN for blocks without elements: their faces are skipped). Both NaN if no face has a
// declared element.
SurfaceLayer surfaceLayer(const Mesh& mesh, const FaceSet& faces,
                          const std::vector<double>& blockYoung);

}  // namespace cc
