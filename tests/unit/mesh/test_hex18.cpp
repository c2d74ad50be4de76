// Solid-shell preparation: Hex27 -> Hex18 keeps every element's volume (integrated with an
// independent biquadratic x linear map) and drops exactly the mid-thickness layer;
// orientThickness puts the local zeta axis along the requested global axis.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <set>

#include "common/errors.hpp"
#include "mesh/gmsh_import.hpp"
#include "mesh/hex18.hpp"
#include "mesh/mesh_checks.hpp"
#include "mesh_test_utils.hpp"

namespace cc {
namespace {

// 1D quadratic Lagrange polynomials on -1, 0, 1 and their derivatives.
Eigen::Vector3d quadratic(double x) {
  return {0.5 * x * (x - 1), 1 - x * x, 0.5 * x * (x + 1)};
}
Eigen::Vector3d quadraticDerivative(double x) {
  return {x - 0.5, -2 * x, x + 0.5};
}

// Volume of an 18-node solid-shell element: Quad9 (corners, mid-edges 01,12,23,30, centre) in
// each of the layers zeta = -1 (nodes 0-8) and +1 (9-17), linear in zeta; 3 x 3 x 2 Gauss
// integrates the determinant (degree <= 5 in xi, eta and 2 in zeta) exactly.
double hex18Volume(const Eigen::Matrix<double, 3, 18>& nodes) {
  // Quad9 node k sits at (quadIndex[k][0], quadIndex[k][1]) of the 1D nodes -1, 0, 1.
  constexpr int quadIndex[9][2] = {{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 0},
                                   {2, 1}, {1, 2}, {0, 1}, {1, 1}};
  const double gauss3[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  const double weight3[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  const double gauss2 = 1 / std::sqrt(3.0);
  double volume = 0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (double zeta : {-gauss2, gauss2}) {
        const Eigen::Vector3d lx = quadratic(gauss3[i]), dlx = quadraticDerivative(gauss3[i]);
        const Eigen::Vector3d ly = quadratic(gauss3[j]), dly = quadraticDerivative(gauss3[j]);
        Eigen::Matrix3d jacobian = Eigen::Matrix3d::Zero();
        for (int k = 0; k < 18; ++k) {
          const int a = quadIndex[k % 9][0], b = quadIndex[k % 9][1];
          const double side = k < 9 ? -1.0 : 1.0;
          const double lz = 0.5 * (1 + side * zeta), dlz = 0.5 * side;
          const Eigen::Vector3d dN(dlx(a) * ly(b) * lz, lx(a) * dly(b) * lz, lx(a) * ly(b) * dlz);
          jacobian += nodes.col(k) * dN.transpose();
        }
        volume += weight3[i] * weight3[j] * jacobian.determinant();
      }
    }
  }
  return volume;
}

Eigen::Matrix<double, 3, 18> shellNodes(const Mesh& mesh, const ElementBlock& block, int e) {
  Eigen::Matrix<double, 3, 18> nodes;
  for (int k = 0; k < 18; ++k) nodes.col(k) = mesh.coordinates.col(block.connectivity(e, k));
  return nodes;
}

std::set<int> rowNodes(const Connectivity& connectivity, int row) {
  std::set<int> nodes;
  for (int k = 0; k < connectivity.cols(); ++k) nodes.insert(connectivity(row, k));
  return nodes;
}

TEST(Hex18, PlateConversionKeepsVolumeAndDropsTheMidLayer) {
  const int nx = 3, ny = 2;
  const double a = 6, b = 4, t = 0.3;
  Mesh mesh = test::loadExample("plate_quadratic.geo",
                                {{"nx", nx}, {"ny", ny}, {"a", a}, {"b", b}, {"t", t}});
  const Mesh solid = mesh;
  convertToSolidShell18(mesh, 0);
  const ElementBlock& shell = mesh.blocks[0];
  ASSERT_EQ(shell.type, CellType::Hex18);
  ASSERT_EQ(shell.connectivity.cols(), 18);
  ASSERT_EQ(shell.connectivity.rows(), nx * ny);
  double total = 0;
  std::set<int> used;
  for (int e = 0; e < nx * ny; ++e) {
    const std::set<int> before = rowNodes(solid.blocks[0].connectivity, e);
    const std::set<int> after = rowNodes(shell.connectivity, e);
    EXPECT_EQ(after.size(), 18u);
    int dropped = 0;
    for (int node : before) {
      if (after.count(node)) continue;
      ++dropped;
      EXPECT_NEAR(mesh.coordinates(2, node), 0.5 * t, 1e-12);  // the mid-thickness layer
    }
    EXPECT_EQ(dropped, 9);
    used.insert(after.begin(), after.end());
    const double volume = hex18Volume(shellNodes(mesh, shell, e));
    EXPECT_NEAR(volume, test::hex8Volume(test::elementCorners(solid, solid.blocks[0], e)), 1e-13);
    total += volume;
    // Thickness (local zeta) is the extrusion direction z: node k+9 sits above node k.
    for (int k = 0; k < 9; ++k) {
      const Eigen::Vector3d across = mesh.coordinates.col(shell.connectivity(e, k + 9)) -
                                     mesh.coordinates.col(shell.connectivity(e, k));
      EXPECT_NEAR((across - Eigen::Vector3d(0, 0, t)).norm(), 0.0, 1e-12);
    }
  }
  EXPECT_NEAR(total, a * b * t, 1e-12 * a * b * t);
  const int layerNodes = (2 * nx + 1) * (2 * ny + 1);
  EXPECT_EQ(used.size(), static_cast<size_t>(2 * layerNodes));
  EXPECT_EQ(mesh.numNodes(), 3 * layerNodes);  // dropped nodes stay, as orphans
  EXPECT_EQ(mesh.nodeSets.at("plate").nodes.size(), static_cast<size_t>(2 * layerNodes));
  EXPECT_EQ(mesh.nodeSets.at("top").nodes.size(), static_cast<size_t>(layerNodes));
  EXPECT_EQ(mesh.nodeSets.at("xmin").nodes.size(), static_cast<size_t>(2 * (2 * ny + 1)));
  // Top and bottom face sets are unchanged and made of their owners' nodes.
  for (const char* name : {"top", "bottom"}) {
    const FaceSet& set = mesh.faceSets.at(name);
    EXPECT_EQ(set.connectivity, solid.faceSets.at(name).connectivity);
    for (int f = 0; f < set.connectivity.rows(); ++f) {
      const std::set<int> owner = rowNodes(shell.connectivity, set.ownerElement[f]);
      for (int k = 0; k < 9; ++k) EXPECT_TRUE(owner.count(set.connectivity(f, k)));
    }
    EXPECT_EQ(test::inwardFaceCount(mesh, set), 0);
  }
  EXPECT_NO_THROW(checkElementJacobians(mesh, {}));
}

TEST(Hex18, ConversionNeedsHex27) {
  Mesh mesh = test::loadExample("cube.geo");
  EXPECT_THROW(convertToSolidShell18(mesh, 0), std::invalid_argument);
  EXPECT_THROW(convertToSolidShell18(mesh, 1), std::invalid_argument);
}

// Unit vectors between opposite face centres of a Hex8/Hex27 (columns: xi, eta, zeta), i.e. the
// directions of the local axes at the element centre.
Eigen::Matrix3d localAxes(const Mesh& mesh, const ElementBlock& block, int e) {
  const Eigen::Matrix<double, 3, 8> corners = test::elementCorners(mesh, block, e);
  constexpr int kLow[3][4] = {{0, 3, 4, 7}, {0, 1, 4, 5}, {0, 1, 2, 3}};
  constexpr int kHigh[3][4] = {{1, 2, 5, 6}, {3, 2, 7, 6}, {4, 5, 6, 7}};
  Eigen::Matrix3d axes;
  for (int axis = 0; axis < 3; ++axis) {
    Eigen::Vector3d difference = Eigen::Vector3d::Zero();
    for (int c = 0; c < 4; ++c)
      difference += corners.col(kHigh[axis][c]) - corners.col(kLow[axis][c]);
    axes.col(axis) = difference.normalized();
  }
  return axes;
}

Eigen::Vector3d zetaDirection(const Mesh& mesh, const ElementBlock& block, int e) {
  return localAxes(mesh, block, e).col(2);
}

TEST(OrientThickness, CantileverZetaFollowsEachGlobalAxis) {
  const Mesh original = test::loadExample("cantilever.geo", {{"nx", 4}});
  for (int axis = 0; axis < 3; ++axis) {
    Mesh mesh = original;
    orientThickness(mesh, 0, axis);
    const ElementBlock& beam = mesh.blocks[0];
    for (int e = 0; e < beam.connectivity.rows(); ++e) {
      // gmsh's transfinite node coordinates carry rounding errors of ~1e-12.
      EXPECT_NEAR((zetaDirection(mesh, beam, e) - Eigen::Vector3d::Unit(axis)).norm(), 0.0, 1e-10)
          << "axis " << axis << " element " << e;
      EXPECT_EQ(rowNodes(beam.connectivity, e), rowNodes(original.blocks[0].connectivity, e));
    }
    EXPECT_NO_THROW(checkElementJacobians(mesh, {}));
    EXPECT_NEAR(test::blockVolume(mesh, beam), 10.0, 1e-12);
    EXPECT_EQ(test::inwardFaceCount(mesh, mesh.faceSets.at("tip")), 0);
  }
}

TEST(OrientThickness, DistortedCubePicksTheClosestAxisPointingForward) {
  const Mesh original = test::loadExample("cube.geo", {{"n", 2}, {"distort", 0.7}});
  for (int axis = 0; axis < 3; ++axis) {
    Mesh mesh = original;
    orientThickness(mesh, 0, axis);
    const ElementBlock& cube = mesh.blocks[0];
    for (int e = 0; e < cube.connectivity.rows(); ++e) {
      // Zeta is, among the element's three local directions, the one closest to the axis.
      const Eigen::Vector3d cosines = localAxes(mesh, cube, e).row(axis).transpose();
      EXPECT_GT(cosines(2), 0.0) << "axis " << axis << " element " << e;
      EXPECT_GT(cosines(2), std::abs(cosines(0))) << "axis " << axis << " element " << e;
      EXPECT_GT(cosines(2), std::abs(cosines(1))) << "axis " << axis << " element " << e;
      EXPECT_EQ(rowNodes(cube.connectivity, e), rowNodes(original.blocks[0].connectivity, e));
    }
    EXPECT_NO_THROW(checkElementJacobians(mesh, {}));
    EXPECT_NEAR(test::blockVolume(mesh, cube), 1.0, 1e-12);
  }
}

TEST(OrientThickness, Hex27CubeBecomesShellsAcrossX) {
  const auto dir = test::scratchDir("hex27_cube");
  test::writeText(dir / "cube27.geo",
                  "Include \"" + test::meshesDir() +
                      "/cube.geo\";\n"
                      "Mesh.ElementOrder = 2;\nMesh.SecondOrderIncomplete = 0;\n");
  MeshSpec spec;
  spec.path = (dir / "cube27.geo").string();
  spec.parameters = {{"n", 2}};
  Mesh mesh = loadMesh(spec);
  ASSERT_EQ(mesh.blocks[0].type, CellType::Hex27);
  orientThickness(mesh, 0, 0);
  EXPECT_NO_THROW(checkElementJacobians(mesh, {}));
  convertToSolidShell18(mesh, 0);
  const ElementBlock& shell = mesh.blocks[0];
  double total = 0;
  for (int e = 0; e < shell.connectivity.rows(); ++e) {
    for (int k = 0; k < 9; ++k) {
      const Eigen::Vector3d across = mesh.coordinates.col(shell.connectivity(e, k + 9)) -
                                     mesh.coordinates.col(shell.connectivity(e, k));
      EXPECT_NEAR((across - Eigen::Vector3d(0.5, 0, 0)).norm(), 0.0, 1e-12);
    }
    total += hex18Volume(shellNodes(mesh, shell, e));
  }
  EXPECT_NEAR(total, 1.0, 1e-12);
  EXPECT_THROW(orientThickness(mesh, 0, 0), std::invalid_argument);  // Hex18 now
}

}  // namespace
}  // namespace cc
