// Independent geometric references for the mesh tests (see mesh_test_utils.hpp).
#include "mesh_test_utils.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <fstream>

#include "mesh/gmsh_import.hpp"

namespace cc::test {
namespace {

// Reference-cube corner signs in gmsh's Hex8 order.
constexpr double kCornerSign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                      {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
constexpr double kQuadCornerSign[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
const double kGaussPoint = 1.0 / std::sqrt(3.0);  // 2-point Gauss abscissa, weights 1

}  // namespace

std::string meshesDir() {
  return std::string(COVCONTACT_SOURCE_DIR) + "/meshes";
}

std::filesystem::path scratchDir(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::path(COVCONTACT_BINARY_DIR) / "test_mesh_scratch" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

void writeText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

Mesh loadExample(const std::string& file, const std::map<std::string, double>& parameters) {
  MeshSpec spec;
  spec.path = meshesDir() + "/" + file;
  spec.parameters = parameters;
  spec.where = {"test.deck", 1, 1};
  return loadMesh(spec);
}

double hex8Volume(const Eigen::Matrix<double, 3, 8>& corners) {
  double volume = 0;
  for (double xi : {-kGaussPoint, kGaussPoint}) {
    for (double eta : {-kGaussPoint, kGaussPoint}) {
      for (double zeta : {-kGaussPoint, kGaussPoint}) {
        Eigen::Matrix3d jacobian = Eigen::Matrix3d::Zero();
        for (int k = 0; k < 8; ++k) {
          const double a = kCornerSign[k][0], b = kCornerSign[k][1], c = kCornerSign[k][2];
          const Eigen::Vector3d dN(a * (1 + b * eta) * (1 + c * zeta) / 8,
                                   b * (1 + a * xi) * (1 + c * zeta) / 8,
                                   c * (1 + a * xi) * (1 + b * eta) / 8);
          jacobian += corners.col(k) * dN.transpose();
        }
        volume += jacobian.determinant();
      }
    }
  }
  return volume;
}

Eigen::Matrix<double, 3, 8> elementCorners(const Mesh& mesh, const ElementBlock& block, int e) {
  Eigen::Matrix<double, 3, 8> corners;
  for (int k = 0; k < 8; ++k) corners.col(k) = mesh.coordinates.col(block.connectivity(e, k));
  return corners;
}

double blockVolume(const Mesh& mesh, const ElementBlock& block) {
  double volume = 0;
  for (int e = 0; e < block.connectivity.rows(); ++e)
    volume += hex8Volume(elementCorners(mesh, block, e));
  return volume;
}

double quad4Area(const Eigen::Matrix<double, 3, 4>& corners) {
  double area = 0;
  for (double xi : {-kGaussPoint, kGaussPoint}) {
    for (double eta : {-kGaussPoint, kGaussPoint}) {
      Eigen::Vector3d dXi = Eigen::Vector3d::Zero(), dEta = Eigen::Vector3d::Zero();
      for (int k = 0; k < 4; ++k) {
        const double a = kQuadCornerSign[k][0], b = kQuadCornerSign[k][1];
        dXi += corners.col(k) * a * (1 + b * eta) / 4;
        dEta += corners.col(k) * b * (1 + a * xi) / 4;
      }
      area += dXi.cross(dEta).norm();
    }
  }
  return area;
}

Eigen::Vector3d quad4Normal(const Eigen::Matrix<double, 3, 4>& corners) {
  return (corners.col(2) - corners.col(0)).cross(corners.col(3) - corners.col(1));
}

Eigen::Matrix<double, 3, 4> faceCorners(const Mesh& mesh, const FaceSet& set, int face) {
  Eigen::Matrix<double, 3, 4> corners;
  for (int c = 0; c < 4; ++c) corners.col(c) = mesh.coordinates.col(set.connectivity(face, c));
  return corners;
}

double faceSetArea(const Mesh& mesh, const FaceSet& set) {
  double area = 0;
  for (int f = 0; f < set.connectivity.rows(); ++f) area += quad4Area(faceCorners(mesh, set, f));
  return area;
}

int inwardFaceCount(const Mesh& mesh, const FaceSet& set) {
  int inward = 0;
  for (int f = 0; f < set.connectivity.rows(); ++f) {
    const ElementBlock& owner = mesh.blocks.at(set.ownerBlock.at(f));
    // The mean of all element nodes lies inside any of our (convex-ish) hexahedra.
    Eigen::Vector3d ownerCentroid = Eigen::Vector3d::Zero();
    const auto row = owner.connectivity.row(set.ownerElement.at(f));
    for (int node : row) ownerCentroid += mesh.coordinates.col(node) / row.size();
    const Eigen::Matrix<double, 3, 4> corners = faceCorners(mesh, set, f);
    const Eigen::Vector3d faceCentroid = corners.rowwise().mean();
    if (quad4Normal(corners).dot(faceCentroid - ownerCentroid) <= 0) ++inward;
  }
  return inward;
}

}  // namespace cc::test
