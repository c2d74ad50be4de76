// Reference-configuration checks of a mesh: positive Jacobians of the volume elements and the
// outward orientation of face sets (matched to their owning volume element by corner nodes).
#include "mesh/mesh_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <unordered_map>
#include <vector>

#include "common/errors.hpp"
#include "mesh/reference_cells.hpp"

namespace cc {
namespace {

// "gmsh element 17" when the tag is known, else "element 3" (0-based index in its block/set).
std::string elementLabel(const std::vector<std::size_t>& gmshTags, int index) {
  if (index < static_cast<int>(gmshTags.size()))
    return fmt::format("gmsh element {}", gmshTags[index]);
  return fmt::format("element {}", index);
}

// Local points where det J must be positive: the nodes and the centre. This is the usual
// validity sampling of finite element codes (a necessary, not a sufficient condition), which
// catches inverted node orderings and collapsed or badly folded elements.
std::vector<Eigen::Vector3d> jacobianCheckPoints(CellType type) {
  std::vector<Eigen::Vector3d> points;
  for (int node = 0; node < nodesPerCell(type); ++node)
    points.push_back(cells::localNode(type, node));
  const Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  if (cells::nodeAt(type, centre) < 0) points.push_back(centre);
  return points;
}

Eigen::Matrix3Xd elementNodes(const Mesh& mesh, const ElementBlock& block, int element) {
  Eigen::Matrix3Xd nodes(3, block.connectivity.cols());
  for (int k = 0; k < nodes.cols(); ++k)
    nodes.col(k) = mesh.coordinates.col(block.connectivity(element, k));
  return nodes;
}

// Sorted corner nodes: the key under which a face is found regardless of its orientation.
using FaceKey = std::array<int, 4>;

// Polynomial hash of the four node numbers; the multiplier is a prime larger than typical node
// counts, so distinct keys rarely collide.
struct FaceKeyHash {
  std::size_t operator()(const FaceKey& key) const {
    constexpr std::size_t kMultiplier = 1000003u;
    std::size_t hash = 0;
    for (int node : key) hash = hash * kMultiplier + static_cast<std::size_t>(node);
    return hash;
  }
};

struct FaceOwner {
  int block = -1;
  int element = -1;
  int localFace = -1;
  int count = 0;  // number of volume elements having this face: 1 on the boundary
};

using FaceOwners = std::unordered_map<FaceKey, FaceOwner, FaceKeyHash>;

FaceKey sortedCorners(const std::array<int, 4>& corners) {
  FaceKey key = corners;
  std::sort(key.begin(), key.end());
  return key;
}

FaceOwners collectVolumeFaces(const Mesh& mesh) {
  FaceOwners owners;
  for (int b = 0; b < static_cast<int>(mesh.blocks.size()); ++b) {
    const ElementBlock& block = mesh.blocks[b];
    if (block.type != CellType::Hex8 && block.type != CellType::Hex27) continue;
    const auto& faces = cells::hexFaces(block.type);
    for (int e = 0; e < block.connectivity.rows(); ++e) {
      for (int f = 0; f < 6; ++f) {
        std::array<int, 4> corners;
        for (int c = 0; c < 4; ++c) corners[c] = block.connectivity(e, faces[f].corners[c]);
        FaceOwner& owner = owners[sortedCorners(corners)];
        owner = {b, e, f, owner.count + 1};
      }
    }
  }
  return owners;
}

// The face's nodes in the owner's outward order, rotated so that `firstCorner` comes first.
Eigen::VectorXi outwardFaceNodes(const ElementBlock& owner, int element, int localFace,
                                 int firstCorner) {
  const cells::HexFace& face = cells::hexFaces(owner.type)[localFace];
  int shift = 0;
  while (shift < 4 && owner.connectivity(element, face.corners[shift]) != firstCorner) ++shift;
  const bool quadratic = owner.type == CellType::Hex27;
  Eigen::VectorXi nodes(quadratic ? 9 : 4);
  for (int c = 0; c < 4; ++c) {
    nodes(c) = owner.connectivity(element, face.corners[(c + shift) % 4]);
    if (quadratic) nodes(4 + c) = owner.connectivity(element, face.midEdges[(c + shift) % 4]);
  }
  if (quadratic) nodes(8) = owner.connectivity(element, face.centre);
  return nodes;
}

bool sameNodeSet(Eigen::VectorXi a, Eigen::VectorXi b) {
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  return a == b;
}

void orientFaceSet(const Mesh& mesh, const FaceOwners& owners, FaceSet& set,
                   const SourceLocation& where) {
  const int faceCount = static_cast<int>(set.connectivity.rows());
  set.ownerBlock.assign(faceCount, -1);
  set.ownerElement.assign(faceCount, -1);
  for (int i = 0; i < faceCount; ++i) {
    std::array<int, 4> corners;
    for (int c = 0; c < 4; ++c) corners[c] = set.connectivity(i, c);
    const auto found = owners.find(sortedCorners(corners));
    const std::string face = elementLabel(set.gmshElementTags, i);
    if (found == owners.end()) {
      throw InputError(where, fmt::format("face set '{}': {} is not a face of any volume element; "
                                          "a physical surface must lie on the boundary of a "
                                          "meshed physical volume",
                                          set.name, face));
    }
    const FaceOwner& owner = found->second;
    if (owner.count > 1) {
      throw InputError(where, fmt::format("face set '{}': {} is an interior face shared by {} "
                                          "volume elements, not a boundary face (do two bodies "
                                          "share nodes?)",
                                          set.name, face, owner.count));
    }
    const ElementBlock& block = mesh.blocks[owner.block];
    const CellType expected = block.type == CellType::Hex27 ? CellType::Quad9 : CellType::Quad4;
    if (set.type != expected) {
      throw InputError(where, fmt::format("face set '{}': {} is a {} face of a {} element of "
                                          "block '{}' (expected {})",
                                          set.name, face, toString(set.type), toString(block.type),
                                          block.name, toString(expected)));
    }
    const Eigen::VectorXi oriented =
        outwardFaceNodes(block, owner.element, owner.localFace, corners[0]);
    if (!sameNodeSet(oriented, set.connectivity.row(i).transpose())) {
      throw InputError(where, fmt::format("face set '{}': the mid-side nodes of {} differ from "
                                          "those of its volume element",
                                          set.name, face));
    }
    set.connectivity.row(i) = oriented.transpose();
    set.ownerBlock[i] = owner.block;
    set.ownerElement[i] = owner.element;
  }
}

}  // namespace

void checkElementJacobians(const Mesh& mesh, const SourceLocation& where) {
  for (const ElementBlock& block : mesh.blocks) {
    const std::vector<Eigen::Vector3d> points = jacobianCheckPoints(block.type);
    for (int e = 0; e < block.connectivity.rows(); ++e) {
      const Eigen::Matrix3Xd nodes = elementNodes(mesh, block, e);
      for (const Eigen::Vector3d& xi : points) {
        const double determinant = cells::jacobianDeterminant(block.type, nodes, xi);
        if (determinant > 0) continue;
        throw InputError(where, fmt::format("inverted element: {} of group '{}' has Jacobian "
                                            "determinant {:.6g} at local point ({:g}, {:g}, {:g}); "
                                            "its nodes are out of order or the element is "
                                            "degenerate",
                                            elementLabel(block.gmshElementTags, e), block.name,
                                            determinant, xi(0), xi(1), xi(2)));
      }
    }
  }
}

void orientFaceSets(Mesh& mesh, const SourceLocation& where) {
  if (mesh.faceSets.empty()) return;
  const FaceOwners owners = collectVolumeFaces(mesh);
  for (auto& [name, set] : mesh.faceSets) orientFaceSet(mesh, owners, set, where);
}

}  // namespace cc
