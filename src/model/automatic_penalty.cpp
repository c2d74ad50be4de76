// Automatic contact penalty: E/h of the elements adjacent to a contact surface.
#include "model/automatic_penalty.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

namespace cc {

namespace {

// Twice the distance from the face centre to the owner element's centre along the face normal
// (nodal means: exact centres for undistorted elements of any order).
double layerThickness(const Mesh& mesh, const FaceSet& faces, int face) {
  const ElementBlock& block = mesh.blocks[faces.ownerBlock[face]];
  const int element = faces.ownerElement[face];
  Eigen::Vector3d elementCentre = Eigen::Vector3d::Zero();
  for (Eigen::Index k = 0; k < block.connectivity.cols(); ++k)
    elementCentre += mesh.coordinates.col(block.connectivity(element, k));
  elementCentre /= static_cast<double>(block.connectivity.cols());
  // The corners (first four nodes of Quad4 and Quad9) give the centre and the normal.
  Eigen::Vector3d corner[4];
  for (int k = 0; k < 4; ++k) corner[k] = mesh.coordinates.col(faces.connectivity(face, k));
  const Eigen::Vector3d faceCentre = 0.25 * (corner[0] + corner[1] + corner[2] + corner[3]);
  const Eigen::Vector3d normal = (corner[2] - corner[0]).cross(corner[3] - corner[1]).normalized();
  return 2.0 * std::abs((elementCentre - faceCentre).dot(normal));
}

}  // namespace

// The means over the faces whose element has a Young's modulus and a positive h.
SurfaceLayer surfaceLayer(const Mesh& mesh, const FaceSet& faces,
                          const std::vector<double>& blockYoung) {
  double stiffness = 0, depth = 0;
  int count = 0;
  for (Eigen::Index face = 0; face < faces.connectivity.rows(); ++face) {
    if (faces.ownerBlock.empty()) break;
    const double young = blockYoung[faces.ownerBlock[face]];
    if (!std::isfinite(young)) continue;
    const double h = layerThickness(mesh, faces, static_cast<int>(face));
    if (!(h > 0)) continue;
    stiffness += young / h;
    depth += h;
    ++count;
  }
  if (count == 0) {
    const double unknown = std::numeric_limits<double>::quiet_NaN();
    return {unknown, unknown};
  }
  return {stiffness / count, depth / count};
}

}  // namespace cc
