// Shared helpers of the mesh tests: paths, temporary files, and independent geometric
// reference computations (trilinear hexahedron volume, bilinear quadrilateral area and normal)
// written without the module's own shape functions.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <string>

#include "mesh/mesh.hpp"

namespace cc::test {

std::string meshesDir();  // <source>/meshes

// A fresh, empty directory for one test's files under the build tree.
std::filesystem::path scratchDir(const std::string& name);
void writeText(const std::filesystem::path& path, const std::string& text);

// loadMesh of <source>/meshes/<file> with the given parameters.
Mesh loadExample(const std::string& file, const std::map<std::string, double>& parameters = {});

// Volume of a trilinear hexahedron (gmsh corner order) by 2 x 2 x 2 Gauss (exact for it).
double hex8Volume(const Eigen::Matrix<double, 3, 8>& corners);
// Corner coordinates (first 8 nodes) of element `e` of `block`.
Eigen::Matrix<double, 3, 8> elementCorners(const Mesh& mesh, const ElementBlock& block, int e);
double blockVolume(const Mesh& mesh, const ElementBlock& block);

// Area of the bilinear quadrilateral on four corners (in order) by 2 x 2 Gauss, and the
// right-hand normal of that order (cross product of the diagonals, not normalized).
double quad4Area(const Eigen::Matrix<double, 3, 4>& corners);
Eigen::Vector3d quad4Normal(const Eigen::Matrix<double, 3, 4>& corners);
Eigen::Matrix<double, 3, 4> faceCorners(const Mesh& mesh, const FaceSet& set, int face);
double faceSetArea(const Mesh& mesh, const FaceSet& set);

// Number of faces of `set` whose normal does not point out of its owner element, i.e. with
// normal . (face centroid - owner centroid) <= 0.
int inwardFaceCount(const Mesh& mesh, const FaceSet& set);

}  // namespace cc::test
