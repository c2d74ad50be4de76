// Synthetic mesh and step records for the output tests (see synthetic_run.hpp).
#include "synthetic_run.hpp"

#include <array>
#include <cmath>

namespace cc::test {

namespace {

// gmsh Hexahedron27 node positions in (u, v, w) in [0, 1]^3: corners, mid-edges 01, 03, 04, 12,
// 15, 23, 26, 37, 45, 47, 56, 67, face centres (0123), (0154), (0374), (1265), (2376), (4567),
// body centre (gmsh reference manual, "Node ordering").
const std::array<Eigen::Vector3d, 27> kGmshHex27 = {{
    {0, 0, 0},   {1, 0, 0},   {1, 1, 0},   {0, 1, 0},   {0, 0, 1},   {1, 0, 1},    {1, 1, 1},
    {0, 1, 1},   {.5, 0, 0},  {0, .5, 0},  {0, 0, .5},  {1, .5, 0},  {1, 0, .5},   {.5, 1, 0},
    {1, 1, .5},  {0, 1, .5},  {.5, 0, 1},  {0, .5, 1},  {1, .5, 1},  {.5, 1, 1},   {.5, .5, 0},
    {.5, 0, .5}, {0, .5, .5}, {1, .5, .5}, {.5, 1, .5}, {.5, .5, 1}, {.5, .5, .5},
}};

// Hex18 as in mesh.hpp: bottom Quad9 (corners ccw, mid-edges 01 12 23 30, centre), then top.
const std::array<Eigen::Vector2d, 9> kQuad9 = {{
    {0, 0},
    {1, 0},
    {1, 1},
    {0, 1},
    {.5, 0},
    {1, .5},
    {.5, 1},
    {0, .5},
    {.5, .5},
}};

constexpr int kBaseCells = 2;  // base block: kBaseCells x kBaseCells x 1 unit cubes
constexpr int kPair1Points = 5;
constexpr int kPair2Points = 3;  // from step 2 on; pair2 has no points in step 1

int baseNode(int i, int j, int k) {
  return i + (kBaseCells + 1) * (j + (kBaseCells + 1) * k);
}

// A smooth value that differs for every (step, index, component) combination.
double wave(int step, int index, int component, double scale) {
  return scale * (std::sin(0.7 * step + 1.3 * index + 2.1 * component) + 0.05 * step);
}

void appendNodes(Mesh& mesh, const std::vector<Eigen::Vector3d>& points) {
  const Eigen::Index first = mesh.coordinates.cols();
  mesh.coordinates.conservativeResize(3, first + static_cast<Eigen::Index>(points.size()));
  for (size_t p = 0; p < points.size(); ++p)
    mesh.coordinates.col(first + static_cast<Eigen::Index>(p)) = points[p];
}

ElementBlock placedBlock(Mesh& mesh, const BlockPlacement& placement, CellType type,
                         const std::vector<Eigen::Vector3d>& natural) {
  const int first = mesh.numNodes();
  std::vector<Eigen::Vector3d> points;
  for (const Eigen::Vector3d& uvw : natural)
    points.push_back(placement.origin + placement.edges * uvw);
  appendNodes(mesh, points);
  ElementBlock block;
  block.name = placement.block;
  block.type = type;
  block.connectivity.resize(1, static_cast<Eigen::Index>(natural.size()));
  for (Eigen::Index n = 0; n < block.connectivity.cols(); ++n)
    block.connectivity(0, n) = first + static_cast<int>(n);
  return block;
}

ContactPairRecord syntheticPair(const std::string& name, int step, int points, int pairIndex) {
  ContactPairRecord pair;
  pair.name = name;
  const int offset = 100 * pairIndex;
  pair.position.resize(3, points);
  pair.tangentialTraction.resize(3, points);
  pair.gap.resize(points);
  pair.normalTraction.resize(points);
  pair.state.resize(points);
  pair.slipIncrement.resize(points);
  pair.accumulatedSlip.resize(points);
  pair.weight.resize(points);
  pair.edgeShare.resize(points);
  for (int p = 0; p < points; ++p) {
    for (int c = 0; c < 3; ++c) {
      pair.position(c, p) = wave(step, offset + p, c, 1.0) + 2.0 * c;
      pair.tangentialTraction(c, p) = wave(step, offset + p, c + 3, 1e3);
    }
    pair.gap(p) = wave(step, offset + p, 6, 1e-3);
    pair.normalTraction(p) = wave(step, offset + p, 7, 2e3);
    pair.state(p) = (p + step + pairIndex) % 3;
    pair.slipIncrement(p) = std::abs(wave(step, offset + p, 8, 1e-4));
    pair.accumulatedSlip(p) = step * std::abs(wave(1, offset + p, 8, 1e-4));
    pair.weight(p) = 0.25 + 0.01 * p;
    pair.edgeShare(p) = p % 4 == 3 ? 1.0 / (2 + p) : 1.0;  // some points beside a free edge
    pair.slaveNodes.push_back(baseNode(p % (kBaseCells + 1), p / (kBaseCells + 1), 1));
  }
  pair.totalForce = Eigen::Vector3d(wave(step, offset, 9, 50), wave(step, offset, 10, 50),
                                    wave(step, offset, 11, 5e3));
  pair.slaveNodalForce.resize(3, points);
  for (int p = 0; p < points; ++p)
    for (int c = 0; c < 3; ++c) pair.slaveNodalForce(c, p) = wave(step, offset + p, 12 + c, 10);
  return pair;
}

}  // namespace

SyntheticMesh makeSyntheticMesh() {
  SyntheticMesh result;
  Mesh& mesh = result.mesh;
  std::vector<Eigen::Vector3d> grid;
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= kBaseCells; ++j)
      for (int i = 0; i <= kBaseCells; ++i) grid.emplace_back(i, j, k);
  appendNodes(mesh, grid);
  ElementBlock base;
  base.name = "base";
  base.type = CellType::Hex8;
  base.connectivity.resize(kBaseCells * kBaseCells, 8);
  for (int j = 0; j < kBaseCells; ++j)
    for (int i = 0; i < kBaseCells; ++i)
      base.connectivity.row(i + kBaseCells * j) << baseNode(i, j, 0), baseNode(i + 1, j, 0),
          baseNode(i + 1, j + 1, 0), baseNode(i, j + 1, 0), baseNode(i, j, 1),
          baseNode(i + 1, j, 1), baseNode(i + 1, j + 1, 1), baseNode(i, j + 1, 1);
  mesh.blocks.push_back(base);

  BlockPlacement cap{"cap27", {0, 0, 2}, Eigen::Matrix3d::Zero()};
  cap.edges << 1, 0.25, 0.1, 0, 1, 0.3, 0, 0, 1.2;
  mesh.blocks.push_back(
      placedBlock(mesh, cap, CellType::Hex27, {kGmshHex27.begin(), kGmshHex27.end()}));
  BlockPlacement shell{"shell18", {3, 0, 0}, Eigen::Matrix3d::Zero()};
  shell.edges << 1.5, 0, 0.2, 0, 1, 0, 0, 0.2, 0.5;
  std::vector<Eigen::Vector3d> hex18;
  for (double w : {0.0, 1.0})
    for (const Eigen::Vector2d& uv : kQuad9) hex18.emplace_back(uv.x(), uv.y(), w);
  mesh.blocks.push_back(placedBlock(mesh, shell, CellType::Hex18, hex18));
  result.placements = {cap, shell};

  for (int k = 0; k <= 1; ++k) {
    NodeSet set{k == 0 ? "bottom" : "top", {}};
    for (int j = 0; j <= kBaseCells; ++j)
      for (int i = 0; i <= kBaseCells; ++i) set.nodes.push_back(baseNode(i, j, k));
    mesh.nodeSets[set.name] = set;
  }
  NodeSet capNodes{"cap, all", {}};
  const Connectivity& capCell = mesh.blocks[1].connectivity;
  for (Eigen::Index n = 0; n < capCell.cols(); ++n) capNodes.nodes.push_back(capCell(0, n));
  mesh.nodeSets[capNodes.name] = capNodes;
  FaceSet top;
  top.name = "base_top";
  top.type = CellType::Quad4;
  top.connectivity = base.connectivity.rightCols(4);
  top.ownerBlock = {0, 0, 0, 0};
  top.ownerElement = {0, 1, 2, 3};
  mesh.faceSets[top.name] = top;
  return result;
}

void fillSyntheticStep(const Mesh& mesh, int step, SyntheticStep& out) {
  const int numNodes = mesh.numNodes();
  Eigen::Index numElements = 0;
  for (const ElementBlock& block : mesh.blocks) numElements += block.connectivity.rows();
  out.displacement.resize(3, numNodes);
  out.reaction.resize(3, numNodes);
  for (int n = 0; n < numNodes; ++n)
    for (int c = 0; c < 3; ++c) {
      out.displacement(c, n) = wave(step, n, c, 1e-2);
      out.reaction(c, n) = wave(step, n, c + 3, 1e4);
    }
  out.stress.resize(6, numElements);
  for (Eigen::Index e = 0; e < numElements; ++e)
    for (int k = 0; k < 6; ++k) out.stress(k, e) = 100.0 * step + 10.0 * e + k + 0.5;
  StepRecord& record = out.record;
  record = StepRecord{};
  record.step = step;
  record.time = 0.1 * step + 0.05 * step * step;
  record.iterations = 3 + step % 3;
  record.cutbacks = step == 2 ? 1 : 0;
  record.displacement = &out.displacement;
  record.reaction = &out.reaction;
  record.stress = &out.stress;
  int setIndex = 0;
  for (const char* name : {"bottom", "top", "cap, all"}) {
    record.setReactions.emplace_back(
        name, Eigen::Vector3d(wave(step, setIndex, 0, 1e3), wave(step, setIndex, 1, 1e3),
                              wave(step, setIndex, 2, 1e5)));
    ++setIndex;
  }
  record.contact.push_back(syntheticPair("pair1", step, kPair1Points, 0));
  record.contact.push_back(syntheticPair("pair2", step, step == 1 ? 0 : kPair2Points, 1));
}

void fillIntegerStep(const Mesh& mesh, int step, SyntheticStep& out) {
  fillSyntheticStep(mesh, step, out);
  for (int n = 0; n < mesh.numNodes(); ++n)
    for (int c = 0; c < 3; ++c) out.displacement(c, n) = 1000.0 * step + 3.0 * n + c;
  out.record.time = 0.5 * step;
  out.record.iterations = step % 4 + 1;
  out.record.setReactions = {{"top", Eigen::Vector3d(step, -step, 0.5)}};
  out.record.contact = {syntheticPair("pair1", step, kPair1Points, 0)};
  out.record.contact.front().totalForce = Eigen::Vector3d(step, 2.0 * step, 3.0 * step);
}

IterationRecord syntheticIteration(int step, int attempt, int iteration) {
  const double residual = std::pow(10.0, -std::pow(2.0, iteration));  // quadratic convergence
  return {step,
          attempt,
          iteration,
          0.1 * step,
          1e3 * residual,
          residual,
          1e2 * residual * residual,
          residual * residual,
          0.01 * (10 * step + iteration)};
}

RunInfo syntheticRunInfo() {
  RunInfo info;
  info.title = "synthetic output test";
  info.version = COVCONTACT_VERSION;
  info.deckPath = "input/synthetic.deck";
  info.commandLine = "covcontact run input/synthetic.deck -o roundtrip.h5";
  info.deckText = "title \"synthetic output test\"\n# deck text with unicode: \xCE\xB5_N = 2.1e6\n";
  return info;
}

}  // namespace cc::test
