// gmsh import of the example geometries: node and element counts against the analytic counts
// of the transfinite meshes, block volumes and face-set areas against the geometry, outward
// face normals, node-set sizes, separate bodies, and .msh round trips.
#include <gtest/gtest.h>

#include <cstdlib>
#include <set>

#include "mesh/gmsh_import.hpp"
#include "mesh_test_utils.hpp"

namespace cc {
namespace {

using test::blockVolume;
using test::faceSetArea;
using test::inwardFaceCount;
using test::loadExample;

// Sums of Gauss-integrated element volumes and areas of a few hundred elements: rounding only.
constexpr double kGeometryTolerance = 1e-12;
// gmsh places transfinite and second-order nodes by evaluating its geometry parametrization;
// positions differ from the exact lattice values by up to ~1e-11 on these 10-20 unit models.
constexpr double kGmshNodeTolerance = 1e-9;

std::set<int> blockNodes(const ElementBlock& block) {
  return std::set<int>(block.connectivity.data(),
                       block.connectivity.data() + block.connectivity.size());
}

void expectFaceSet(const Mesh& mesh, const std::string& name, int faces, double area,
                   const Eigen::Vector3d& outward, const std::string& owner) {
  SCOPED_TRACE("face set " + name);
  ASSERT_TRUE(mesh.faceSets.count(name));
  const FaceSet& set = mesh.faceSets.at(name);
  EXPECT_EQ(set.connectivity.rows(), faces);
  EXPECT_NEAR(faceSetArea(mesh, set), area, kGeometryTolerance * area);
  EXPECT_EQ(inwardFaceCount(mesh, set), 0);
  for (int f = 0; f < faces; ++f) {
    EXPECT_EQ(mesh.blocks[set.ownerBlock[f]].name, owner);
    const Eigen::Vector3d normal = test::quad4Normal(test::faceCorners(mesh, set, f)).normalized();
    EXPECT_NEAR((normal - outward).norm(), 0.0, 1e-12) << "face " << f;
  }
}

TEST(GmshImport, UniformCubeHasAnalyticCountsVolumeAndFaces) {
  const int n = 3;
  const Mesh mesh = loadExample("cube.geo", {{"n", n}});
  EXPECT_EQ(mesh.numNodes(), (n + 1) * (n + 1) * (n + 1));
  ASSERT_EQ(mesh.blocks.size(), 1u);
  EXPECT_EQ(mesh.blocks[0].name, "cube");
  EXPECT_EQ(mesh.blocks[0].type, CellType::Hex8);
  EXPECT_EQ(mesh.blocks[0].connectivity.rows(), n * n * n);
  EXPECT_NEAR(blockVolume(mesh, mesh.blocks[0]), 1.0, kGeometryTolerance);
  const std::pair<std::string, Eigen::Vector3d> faces[] = {
      {"xmin", -Eigen::Vector3d::UnitX()}, {"xmax", Eigen::Vector3d::UnitX()},
      {"ymin", -Eigen::Vector3d::UnitY()}, {"ymax", Eigen::Vector3d::UnitY()},
      {"zmin", -Eigen::Vector3d::UnitZ()}, {"zmax", Eigen::Vector3d::UnitZ()}};
  for (const auto& [name, outward] : faces) {
    expectFaceSet(mesh, name, n * n, 1.0, outward, "cube");
    EXPECT_EQ(mesh.nodeSets.at(name).nodes.size(), static_cast<size_t>((n + 1) * (n + 1)));
  }
  EXPECT_EQ(mesh.nodeSets.at("cube").nodes.size(), static_cast<size_t>(mesh.numNodes()));
  EXPECT_EQ(mesh.gmshNodeTags.size(), static_cast<size_t>(mesh.numNodes()));
  EXPECT_EQ(mesh.blocks[0].gmshElementTags.size(), static_cast<size_t>(n * n * n));
}

TEST(GmshImport, DistortedCubeKeepsVolumeAndOutwardFaces) {
  const int n = 4;
  const Mesh mesh = loadExample("cube.geo", {{"n", n}, {"distort", 0.8}});
  ASSERT_EQ(mesh.blocks[0].connectivity.rows(), n * n * n);
  // The elements really are distorted: their volumes differ from the uniform 1/n^3.
  double smallest = 1.0, largest = 0.0;
  for (int e = 0; e < n * n * n; ++e) {
    const double volume = test::hex8Volume(test::elementCorners(mesh, mesh.blocks[0], e));
    smallest = std::min(smallest, volume);
    largest = std::max(largest, volume);
  }
  EXPECT_GT(largest / smallest, 2.0);
  EXPECT_NEAR(blockVolume(mesh, mesh.blocks[0]), 1.0, kGeometryTolerance);
  for (const char* name : {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"}) {
    EXPECT_EQ(inwardFaceCount(mesh, mesh.faceSets.at(name)), 0) << name;
    EXPECT_NEAR(faceSetArea(mesh, mesh.faceSets.at(name)), 1.0, kGeometryTolerance) << name;
  }
}

TEST(GmshImport, BlockOnBaseHasSeparateBodiesAndNonMatchingInterface) {
  const int nx = 8, ny = 2, nz = 2, nbx = 5, nby = 1;
  const Mesh mesh = loadExample("block_on_base.geo",
                                {{"nx", nx}, {"ny", ny}, {"nz", nz}, {"nbx", nbx}, {"nby", nby}});
  ASSERT_EQ(mesh.blocks.size(), 2u);
  const ElementBlock& block = *mesh.findBlock("block");
  const ElementBlock& base = *mesh.findBlock("base");
  EXPECT_EQ(block.connectivity.rows(), nx * ny * nz);
  EXPECT_EQ(base.connectivity.rows(), nbx * nby * nz);
  const int blockNodeCount = (nx + 1) * (ny + 1) * (nz + 1);
  const int baseNodeCount = (nbx + 1) * (nby + 1) * (nz + 1);
  EXPECT_EQ(mesh.numNodes(), blockNodeCount + baseNodeCount);
  EXPECT_EQ(blockNodes(block).size(), static_cast<size_t>(blockNodeCount));
  EXPECT_EQ(blockNodes(base).size(), static_cast<size_t>(baseNodeCount));
  EXPECT_NEAR(blockVolume(mesh, block), 20 * 5 * 0.5, kGeometryTolerance * 50);
  EXPECT_NEAR(blockVolume(mesh, base), 24 * 1 * 0.5, kGeometryTolerance * 12);

  expectFaceSet(mesh, "block_bottom", nx * nz, 20 * 0.5, -Eigen::Vector3d::UnitY(), "block");
  expectFaceSet(mesh, "base_top", nbx * nz, 24 * 0.5, Eigen::Vector3d::UnitY(), "base");
  expectFaceSet(mesh, "block_top", nx * nz, 20 * 0.5, Eigen::Vector3d::UnitY(), "block");
  expectFaceSet(mesh, "base_bottom", nbx * nz, 24 * 0.5, -Eigen::Vector3d::UnitY(), "base");
  expectFaceSet(mesh, "block_front", nx * ny, 20 * 5, -Eigen::Vector3d::UnitZ(), "block");
  expectFaceSet(mesh, "block_back", nx * ny, 20 * 5, Eigen::Vector3d::UnitZ(), "block");
  expectFaceSet(mesh, "block_left", ny * nz, 5 * 0.5, -Eigen::Vector3d::UnitX(), "block");
  expectFaceSet(mesh, "block_right", ny * nz, 5 * 0.5, Eigen::Vector3d::UnitX(), "block");

  EXPECT_EQ(mesh.nodeSets.at("block_bottom").nodes.size(),
            static_cast<size_t>((nx + 1) * (nz + 1)));
  EXPECT_EQ(mesh.nodeSets.at("base_top").nodes.size(), static_cast<size_t>((nbx + 1) * (nz + 1)));
  const NodeSet& edge = mesh.nodeSets.at("block_bottom_edge");
  ASSERT_EQ(edge.nodes.size(), static_cast<size_t>(nx + 1));
  for (int node : edge.nodes) {
    EXPECT_EQ(mesh.coordinates(1, node), 0.0);
    EXPECT_EQ(mesh.coordinates(2, node), 0.0);
  }
}

TEST(GmshImport, BodiesOfEqualLengthTouchingStillShareNoNodes) {
  const Mesh mesh =
      loadExample("block_on_base.geo", {{"nx", 4}, {"ny", 1}, {"nbx", 4}, {"baseLength", 20}});
  const std::set<int> block = blockNodes(*mesh.findBlock("block"));
  const std::set<int> base = blockNodes(*mesh.findBlock("base"));
  for (int node : block) EXPECT_EQ(base.count(node), 0u) << "shared node " << node;
  // Coincident positions exist (the interface nodes), but as distinct nodes.
  EXPECT_EQ(mesh.numNodes(), static_cast<int>(block.size() + base.size()));
  int coincident = 0;
  for (int a : mesh.nodeSets.at("block_bottom").nodes) {
    for (int b : mesh.nodeSets.at("base_top").nodes) {
      if ((mesh.coordinates.col(a) - mesh.coordinates.col(b)).norm() < kGmshNodeTolerance) {
        ++coincident;
      }
    }
  }
  EXPECT_EQ(coincident, 5 * 2);
}

TEST(GmshImport, GapParameterLiftsTheBlock) {
  const double gap = 0.25;
  const Mesh mesh =
      loadExample("block_on_base.geo", {{"nx", 2}, {"ny", 1}, {"nbx", 2}, {"gap", gap}});
  for (int node : mesh.nodeSets.at("block_bottom").nodes) {
    EXPECT_DOUBLE_EQ(mesh.coordinates(1, node), gap);
  }
  for (int node : mesh.nodeSets.at("base_top").nodes) EXPECT_EQ(mesh.coordinates(1, node), 0.0);
}

TEST(GmshImport, CantileverDefaults) {
  const Mesh mesh = loadExample("cantilever.geo");
  const int nx = 10, ny = 2, nz = 2;
  EXPECT_EQ(mesh.numNodes(), (nx + 1) * (ny + 1) * (nz + 1));
  ASSERT_EQ(mesh.blocks.size(), 1u);
  EXPECT_EQ(mesh.blocks[0].name, "beam");
  EXPECT_EQ(mesh.blocks[0].connectivity.rows(), nx * ny * nz);
  EXPECT_NEAR(blockVolume(mesh, mesh.blocks[0]), 10.0, kGeometryTolerance * 10);
  expectFaceSet(mesh, "clamp", ny * nz, 1.0, -Eigen::Vector3d::UnitX(), "beam");
  expectFaceSet(mesh, "tip", ny * nz, 1.0, Eigen::Vector3d::UnitX(), "beam");
  for (int node : mesh.nodeSets.at("tip").nodes) EXPECT_EQ(mesh.coordinates(0, node), 10.0);
}

TEST(GmshImport, QuadraticPlateIsHex27WithQuad9Faces) {
  const int nx = 3, ny = 2;
  const double a = 6, b = 4, t = 0.2;
  const Mesh mesh =
      loadExample("plate_quadratic.geo", {{"nx", nx}, {"ny", ny}, {"a", a}, {"b", b}, {"t", t}});
  ASSERT_EQ(mesh.blocks.size(), 1u);
  const ElementBlock& plate = mesh.blocks[0];
  EXPECT_EQ(plate.type, CellType::Hex27);
  EXPECT_EQ(plate.connectivity.rows(), nx * ny);
  EXPECT_EQ(mesh.numNodes(), (2 * nx + 1) * (2 * ny + 1) * 3);
  EXPECT_NEAR(blockVolume(mesh, plate), a * b * t, kGeometryTolerance * a * b * t);
  for (const char* name : {"top", "bottom"}) {
    const FaceSet& set = mesh.faceSets.at(name);
    EXPECT_EQ(set.type, CellType::Quad9);
    EXPECT_EQ(mesh.nodeSets.at(name).nodes.size(),
              static_cast<size_t>((2 * nx + 1) * (2 * ny + 1)));
  }
  expectFaceSet(mesh, "top", nx * ny, a * b, Eigen::Vector3d::UnitZ(), "plate");
  expectFaceSet(mesh, "bottom", nx * ny, a * b, -Eigen::Vector3d::UnitZ(), "plate");
  expectFaceSet(mesh, "xmin", ny, b * t, -Eigen::Vector3d::UnitX(), "plate");
  // Quad9 mid-edge and centre nodes sit at the midpoints of the (straight) face.
  const FaceSet& top = mesh.faceSets.at("top");
  for (int f = 0; f < top.connectivity.rows(); ++f) {
    const auto corner = [&](int c) { return mesh.coordinates.col(top.connectivity(f, c)); };
    for (int c = 0; c < 4; ++c) {
      EXPECT_NEAR((mesh.coordinates.col(top.connectivity(f, 4 + c)) -
                   0.5 * (corner(c) + corner((c + 1) % 4)))
                      .norm(),
                  0.0, kGmshNodeTolerance);
    }
    EXPECT_NEAR((mesh.coordinates.col(top.connectivity(f, 8)) -
                 0.25 * (corner(0) + corner(1) + corner(2) + corner(3)))
                    .norm(),
                0.0, kGmshNodeTolerance);
  }
}

TEST(GmshImport, RepeatedImportsAreIndependent) {
  // Options and parameters of one import must not leak into the next (gmsh is re-initialized).
  const Mesh plate = loadExample("plate_quadratic.geo", {{"nx", 1}, {"ny", 1}});
  EXPECT_EQ(plate.blocks[0].type, CellType::Hex27);
  const Mesh coarse = loadExample("cube.geo", {{"n", 2}});
  EXPECT_EQ(coarse.blocks[0].type, CellType::Hex8);
  EXPECT_EQ(coarse.blocks[0].connectivity.rows(), 8);
  const Mesh fine = loadExample("cube.geo", {{"n", 4}});
  EXPECT_EQ(fine.blocks[0].connectivity.rows(), 64);
  const Mesh defaults = loadExample("cube.geo");
  EXPECT_EQ(defaults.blocks[0].connectivity.rows(), 8);
  // Both files declare nx and ny; the cantilever's defaults (10, 2, 2) must apply after the
  // block was meshed with other values (gmsh's ONELAB parameter store persists otherwise).
  loadExample("block_on_base.geo", {{"nx", 3}, {"ny", 1}});
  EXPECT_EQ(loadExample("cantilever.geo").blocks[0].connectivity.rows(), 10 * 2 * 2);
}

// Identical topology; coordinates equal up to `coordinateTolerance` (0 for binary .msh files;
// ASCII .msh files print 16 significant digits, one short of a double's round trip).
void expectIdentical(const Mesh& a, const Mesh& b, double coordinateTolerance) {
  ASSERT_EQ(a.numNodes(), b.numNodes());
  EXPECT_LE((a.coordinates - b.coordinates).cwiseAbs().maxCoeff(),
            coordinateTolerance * a.coordinates.cwiseAbs().maxCoeff());
  EXPECT_EQ(a.gmshNodeTags, b.gmshNodeTags);
  ASSERT_EQ(a.blocks.size(), b.blocks.size());
  for (size_t i = 0; i < a.blocks.size(); ++i) {
    EXPECT_EQ(a.blocks[i].name, b.blocks[i].name);
    EXPECT_EQ(a.blocks[i].type, b.blocks[i].type);
    EXPECT_EQ(a.blocks[i].connectivity, b.blocks[i].connectivity);
    EXPECT_EQ(a.blocks[i].gmshElementTags, b.blocks[i].gmshElementTags);
  }
  ASSERT_EQ(a.faceSets.size(), b.faceSets.size());
  for (const auto& [name, set] : a.faceSets) {
    ASSERT_TRUE(b.faceSets.count(name)) << name;
    const FaceSet& other = b.faceSets.at(name);
    EXPECT_EQ(set.connectivity, other.connectivity) << name;
    EXPECT_EQ(set.ownerBlock, other.ownerBlock) << name;
    EXPECT_EQ(set.ownerElement, other.ownerElement) << name;
  }
  ASSERT_EQ(a.nodeSets.size(), b.nodeSets.size());
  for (const auto& [name, set] : a.nodeSets) {
    ASSERT_TRUE(b.nodeSets.count(name)) << name;
    EXPECT_EQ(set.nodes, b.nodeSets.at(name).nodes) << name;
  }
}

// Writes <dir>/<stem>.msh with the gmsh command-line program and loads both versions.
void expectMshRoundTrip(const std::string& geo, const std::map<std::string, double>& parameters,
                        const std::string& format, bool binary) {
  SCOPED_TRACE(geo + " as " + format);
  const std::filesystem::path dir = test::scratchDir("round_trip_" + format);
  const std::filesystem::path msh = dir / (std::filesystem::path(geo).stem().string() + ".msh");
  std::string command = std::string(GMSH_EXECUTABLE) + " -3 -v 0 -format " + format +
                        (binary ? " -bin " : " ") + test::meshesDir() + "/" + geo + " -o " +
                        msh.string();
  for (const auto& [name, value] : parameters) {
    command += " -setnumber " + name + " " + std::to_string(value);
  }
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const Mesh fromGeo = loadExample(geo, parameters);
  MeshSpec spec;
  spec.path = msh.string();
  const Mesh fromMsh = loadMesh(spec);
  const double asciiRelativeRounding = 1e-15;  // 16 digits: relative error <= 5e-16
  expectIdentical(fromGeo, fromMsh, binary ? 0.0 : asciiRelativeRounding);
}

TEST(GmshImport, MshWrittenByGmshLoadsToTheSameMesh) {
  expectMshRoundTrip("cube.geo", {{"n", 3}, {"distort", 0.5}}, "msh41", true);
  expectMshRoundTrip("block_on_base.geo", {{"nx", 6}, {"nbx", 4}, {"ny", 2}}, "msh22", false);
  expectMshRoundTrip("plate_quadratic.geo", {{"nx", 2}, {"ny", 2}}, "msh41", false);
}

}  // namespace
}  // namespace cc
