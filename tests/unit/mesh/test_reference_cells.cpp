// Reference cells of the mesh module: node tables against gmsh itself, shape functions against
// the Kronecker property, partition of unity and finite differences, hexahedron faces against
// the outward axis directions, Jacobians against affine maps.
#include <gmsh.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "mesh/reference_cells.hpp"

namespace cc {
namespace {

const CellType kAllTypes[] = {CellType::Hex8, CellType::Hex27, CellType::Hex18, CellType::Quad4,
                              CellType::Quad9};

TEST(ReferenceCells, LocalNodesMatchGmshElementProperties) {
  const std::pair<CellType, int> gmshTypes[] = {
      {CellType::Hex8, 5}, {CellType::Hex27, 12}, {CellType::Quad4, 3}, {CellType::Quad9, 10}};
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  for (const auto& [type, gmshType] : gmshTypes) {
    std::string name;
    int dim = 0, order = 0, numNodes = 0, numPrimary = 0;
    std::vector<double> local;
    gmsh::model::mesh::getElementProperties(gmshType, name, dim, order, numNodes, local,
                                            numPrimary);
    ASSERT_EQ(numNodes, nodesPerCell(type)) << name;
    for (int node = 0; node < numNodes; ++node) {
      for (int axis = 0; axis < dim; ++axis) {
        EXPECT_EQ(cells::localNode(type, node)(axis), local[dim * node + axis])
            << name << " node " << node << " axis " << axis;
      }
    }
  }
  gmsh::finalize();
}

TEST(ReferenceCells, Hex18IsHex27WithoutTheMidThicknessLayer) {
  for (int node = 0; node < 18; ++node) {
    const Eigen::Vector3d local = cells::localNode(CellType::Hex18, node);
    EXPECT_EQ(std::abs(local(2)), 1.0);
    EXPECT_GE(cells::nodeAt(CellType::Hex27, local), 0);
    // Quad9 order within each layer: corners, mid-edges 01,12,23,30, centre.
    EXPECT_EQ(local.head<2>(), cells::localNode(CellType::Quad9, node % 9).head<2>());
  }
}

TEST(ReferenceCells, ShapeFunctionsAreNodalAndSumToOne) {
  for (CellType type : kAllTypes) {
    const int count = nodesPerCell(type);
    for (int j = 0; j < count; ++j) {
      const Eigen::VectorXd values = cells::shapeValues(type, cells::localNode(type, j));
      for (int k = 0; k < count; ++k) {
        EXPECT_NEAR(values(k), k == j ? 1.0 : 0.0, 1e-15) << toString(type) << " " << j << " " << k;
      }
    }
    const Eigen::Vector3d point(0.31, -0.72, 0.45);
    EXPECT_NEAR(cells::shapeValues(type, point).sum(), 1.0, 1e-14) << toString(type);
    EXPECT_NEAR(cells::shapeGradients(type, point).rowwise().sum().norm(), 0.0, 1e-14);
  }
}

TEST(ReferenceCells, ShapeGradientsMatchCentralDifferences) {
  // Central differences of a polynomial of degree <= 2 per axis are exact up to rounding:
  // the error is ~ machine epsilon / step.
  const double step = 1e-5;
  const double tolerance = 1e3 * std::numeric_limits<double>::epsilon() / step;
  const Eigen::Vector3d point(-0.27, 0.63, 0.18);
  for (CellType type : kAllTypes) {
    const Eigen::Matrix3Xd gradients = cells::shapeGradients(type, point);
    for (int axis = 0; axis < 3; ++axis) {
      const Eigen::Vector3d offset = step * Eigen::Vector3d::Unit(axis);
      const Eigen::VectorXd difference =
          (cells::shapeValues(type, point + offset) - cells::shapeValues(type, point - offset)) /
          (2 * step);
      EXPECT_LT((gradients.row(axis).transpose() - difference).norm(), tolerance)
          << toString(type) << " axis " << axis;
    }
  }
}

TEST(ReferenceCells, HexFacesAreCounterClockwiseSeenFromOutside) {
  for (CellType type : {CellType::Hex8, CellType::Hex27}) {
    const auto& faces = cells::hexFaces(type);
    for (int f = 0; f < 6; ++f) {
      Eigen::Matrix<double, 3, 4> corners;
      for (int c = 0; c < 4; ++c) corners.col(c) = cells::localNode(type, faces[f].corners[c]);
      const Eigen::Vector3d centre = corners.rowwise().mean();
      // On the reference cube the face centre is the outward unit normal.
      const Eigen::Vector3d normal =
          (corners.col(2) - corners.col(0)).cross(corners.col(3) - corners.col(1)).normalized();
      EXPECT_NEAR((normal - centre).norm(), 0.0, 1e-15) << toString(type) << " face " << f;
      if (type == CellType::Hex8) continue;
      for (int c = 0; c < 4; ++c) {
        EXPECT_EQ(cells::localNode(type, faces[f].midEdges[c]),
                  0.5 * (corners.col(c) + corners.col((c + 1) % 4)));
      }
      EXPECT_EQ(cells::localNode(type, faces[f].centre), centre);
      EXPECT_EQ(faces[f].centre, 20 + f);  // gmsh's face-centre numbering
    }
  }
}

TEST(ReferenceCells, JacobianOfAnAffineMapIsConstant) {
  Eigen::Matrix3d linear;
  linear << 2.0, 0.3, -0.1, 0.2, 1.5, 0.4, -0.3, 0.1, 0.8;
  const Eigen::Vector3d shift(1.0, -2.0, 0.5);
  for (CellType type : {CellType::Hex8, CellType::Hex27, CellType::Hex18}) {
    Eigen::Matrix3Xd nodes(3, nodesPerCell(type));
    for (int k = 0; k < nodes.cols(); ++k)
      nodes.col(k) = linear * cells::localNode(type, k) + shift;
    for (const Eigen::Vector3d& point :
         {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, -1, 1), Eigen::Vector3d(0.3, 0.2, -0.9)}) {
      EXPECT_NEAR(cells::jacobianDeterminant(type, nodes, point), linear.determinant(), 1e-13)
          << toString(type);
    }
  }
}

}  // namespace
}  // namespace cc
