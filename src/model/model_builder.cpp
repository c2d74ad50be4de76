// buildModel: ProblemSpec + mesh -> Model, with every deck reference checked against the mesh.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>

#include "common/errors.hpp"
#include "common/name_matching.hpp"
#include "materials/material.hpp"
#include "mesh/gmsh_import.hpp"
#include "mesh/hex18.hpp"
#include "model/automatic_penalty.hpp"
#include "model/element_factory.hpp"
#include "model/model.hpp"

namespace cc {

namespace {

std::vector<std::string> keysOf(const auto& map) {
  std::vector<std::string> keys;
  for (const auto& entry : map) keys.push_back(entry.first);
  return keys;
}

int findBlock(const Mesh& mesh, const std::string& name) {
  for (std::size_t b = 0; b < mesh.blocks.size(); ++b) {
    if (mesh.blocks[b].name == name) return static_cast<int>(b);
  }
  return -1;
}

std::shared_ptr<const Material> makeMaterial(const MaterialSpec& spec) {
  switch (spec.model) {
    case MaterialSpec::Model::StVenantKirchhoff:
      return makeStVenantKirchhoff(spec.youngsModulus, spec.poissonRatio);
    case MaterialSpec::Model::NeoHooke:
      return makeNeoHooke(spec.youngsModulus, spec.poissonRatio);
    case MaterialSpec::Model::NeoHookeDecoupled:
      return makeNeoHookeDecoupledFromYoung(spec.youngsModulus, spec.poissonRatio);
  }
  throw InputError(spec.where, "unknown material model");
}

// Checks the block's cell type against the element type and prepares it (thickness direction,
// Hex27 -> Hex18). Returns the block index.
int prepareBlock(Mesh& mesh, const ElementBlockSpec& spec) {
  const int block = findBlock(mesh, spec.group);
  if (block < 0) {
    if (mesh.faceSets.count(spec.group)) {
      throw InputError(spec.where, fmt::format("elements: '{}' is a surface group; elements need a "
                                               "volume group",
                                               spec.group));
    }
    std::vector<std::string> names;
    for (const ElementBlock& b : mesh.blocks) names.push_back(b.name);
    throw InputError(spec.where, fmt::format("elements: the mesh has no volume group '{}'{}",
                                             spec.group, deck::didYouMean(spec.group, names)));
  }
  const CellType cell = mesh.blocks[block].type;
  const bool quadratic = spec.type == ElementBlockSpec::Type::SolidShell18;
  if (quadratic && cell != CellType::Hex27) {
    throw InputError(
        spec.where, fmt::format("elements: solid_shell18 needs a quadratic (Hex27) mesh, but group "
                                "'{}' has {} elements; mesh it with second-order hexahedra",
                                spec.group, toString(cell)));
  }
  if (!quadratic && cell != CellType::Hex8) {
    throw InputError(
        spec.where, fmt::format("elements: {} needs linear (Hex8) hexahedra, but group '{}' has {} "
                                "elements",
                                elementTypeName(spec.type), spec.group, toString(cell)));
  }
  if (spec.thicknessAxis >= 0) orientThickness(mesh, block, spec.thicknessAxis);
  if (quadratic) convertToSolidShell18(mesh, block);
  return block;
}

const FaceSet& requireFaceSet(const Mesh& mesh, const std::string& name,
                              const SourceLocation& where, const char* role) {
  const auto it = mesh.faceSets.find(name);
  if (it != mesh.faceSets.end()) return it->second;
  if (findBlock(mesh, name) >= 0) {
    throw InputError(where,
                     fmt::format("contact: {} '{}' is a volume group; a contact surface must "
                                 "be a face (surface) group",
                                 role, name));
  }
  if (name == kAllNodesSet) {
    throw InputError(where, fmt::format("contact: {} '{}' is the built-in set of every node; a "
                                        "contact surface must be a face (surface) group",
                                        role, name));
  }
  if (mesh.nodeSets.count(name)) {
    throw InputError(where, fmt::format("contact: {} '{}' is a curve or point group; a contact "
                                        "surface must be a face (surface) group",
                                        role, name));
  }
  throw InputError(where, fmt::format("contact: the mesh has no face group '{}'{}", name,
                                      deck::didYouMean(name, keysOf(mesh.faceSets))));
}

// Every node of a contact face must belong to a declared element (else: the group's volume has
// no `elements` line, or the faces are lateral faces of converted 18-node solid-shells).
void requireAttached(const FaceSet& faces, const std::vector<bool>& active,
                     const SourceLocation& where) {
  for (Eigen::Index f = 0; f < faces.connectivity.rows(); ++f) {
    for (Eigen::Index k = 0; k < faces.connectivity.cols(); ++k) {
      if (!active[faces.connectivity(f, k)]) {
        throw InputError(where,
                         fmt::format("contact: face group '{}' has nodes that belong to no "
                                     "element (is its volume declared by an `elements` "
                                     "line? lateral faces of solid_shell18 cannot be contact "
                                     "surfaces)",
                                     faces.name));
      }
    }
  }
}

contact::TangentParts contactTangentParts(const TangentPartsSpec& spec) {
  return {.normalMain = spec.normalMain,
          .normalRotational = spec.normalRotational,
          .normalCurvature = spec.normalCurvature,
          .stickMain = spec.stickMain,
          .stickRotational = spec.stickRotational,
          .stickCurvature = spec.stickCurvature,
          .slideConstitutive = spec.slideConstitutive,
          .slideRotational = spec.slideRotational,
          .slideCurvature = spec.slideCurvature,
          .slideUnsymmetricCurvature = spec.slideUnsymmetricCurvature};
}

contact::RigidSurface rigidSurface(const RigidSurfaceSpec& spec) {
  using Shape = contact::RigidSurface::Shape;
  const auto toVector = [](const Vec3& v) { return Eigen::Vector3d(v[0], v[1], v[2]); };
  contact::RigidSurface s;
  switch (spec.shape) {
    case RigidSurfaceSpec::Shape::Plane:
      s.shape = Shape::Plane;
      break;
    case RigidSurfaceSpec::Shape::Cylinder:
      s.shape = Shape::Cylinder;
      break;
    case RigidSurfaceSpec::Shape::ParabolicCylinder:
      s.shape = Shape::ParabolicCylinder;
      break;
    case RigidSurfaceSpec::Shape::Sphere:
      s.shape = Shape::Sphere;
      break;
  }
  s.origin = toVector(spec.origin);
  s.normal = toVector(spec.normal).normalized();
  s.axis = toVector(spec.axis).normalized();
  s.radius = spec.radius;
  s.curvature = spec.curvature;
  return s;
}

contact::ContactPairConfig pairConfig(const ContactSpec& spec) {
  contact::ContactPairConfig config;
  config.name = spec.name;
  switch (spec.kind) {
    case ContactSpec::Kind::NodeToSegment:
      config.kind = contact::PointKind::NodeToSegment;
      break;
    case ContactSpec::Kind::SegmentToSegment:
      config.kind = contact::PointKind::SegmentToSegment;
      break;
    case ContactSpec::Kind::SegmentToAnalytical:
      config.kind = contact::PointKind::SegmentToAnalytical;
      break;
  }
  // The trial-traction integration stays at its documented default (friction_law.hpp).
  config.law = {.penaltyNormal = spec.penaltyNormal,
                .penaltyTangential = spec.penaltyTangential,
                .friction = spec.friction};
  config.augmented = spec.enforcement == ContactSpec::Enforcement::Augmented;
  config.augmentationTolerance = spec.augmentationTolerance;
  config.maxAugmentations = spec.maxAugmentations;
  config.accelerationDepth = spec.accelerationDepth;
  config.growPenalty = spec.growPenalty;
  config.integrationPoints = spec.integrationPoints;
  config.tangentMode = spec.tangentMode == ContactSpec::TangentMode::Exact
                           ? contact::TangentMode::Exact
                           : contact::TangentMode::Paper;
  config.parts = contactTangentParts(spec.parts);
  config.smoothMaster = spec.masterSurface == ContactSpec::MasterSurface::Smooth;
  config.creaseAngle = spec.creaseDegrees * std::numbers::pi / 180;
  config.fadingEdges = spec.masterEdge == ContactSpec::MasterEdge::Fade;
  config.segmentIntegration = spec.integration == ContactSpec::Integration::Segments;
  return config;
}

contact::SurfaceMotion surfaceMotion(const RigidSurfaceSpec& spec) {
  std::vector<std::shared_ptr<ScalarFunction>> components(3);
  for (int c = 0; c < 3; ++c) {
    if (spec.motion[c]) {
      components[c] = makeFunction(*spec.motion[c], FunctionVariables::TimeOnly);
    }
  }
  return [components](double t) {
    Eigen::Vector3d offset = Eigen::Vector3d::Zero();
    for (int c = 0; c < 3; ++c) {
      if (components[c]) offset[c] = (*components[c])(t);
    }
    return offset;
  };
}

// The omitted penalties of a pair (automatic_penalty.hpp): the softer of its two surfaces.
void setAutomaticPenalty(const ContactSpec& spec, const Mesh& mesh,
                         const std::vector<double>& blockYoung,
                         contact::ContactPairConfig& config) {
  const bool normal = spec.penaltyNormal == 0;
  const bool tangential = spec.friction > 0 && spec.penaltyTangential == 0;
  SurfaceLayer layer = surfaceLayer(mesh, mesh.faceSets.at(spec.master), blockYoung);
  if (spec.kind != ContactSpec::Kind::SegmentToAnalytical) {
    // The softer side's (as std::min: a master without elements behind it stays unknown).
    if (const SurfaceLayer slave = surfaceLayer(mesh, mesh.faceSets.at(spec.slave), blockYoung);
        slave.stiffness < layer.stiffness) {
      layer = slave;
    }
  }
  const double stiffness = layer.stiffness, depth = layer.depth;
  const bool known = std::isfinite(stiffness) && stiffness > 0;
  config.layerDepth = known && std::isfinite(depth) ? depth : 0.0;
  // Known for every pair, whatever eps the deck gives (unknown: 0): the augmented Lagrangian's
  // stopping rule measures penetration against it (contact_pair_augmentation.cpp), and a penalty
  // far above it is approached by continuation within each step (solver/load_stepper.cpp).
  config.referencePenalty = known ? kAutomaticPenaltyFactor * stiffness : 0.0;
  if (!normal && !tangential) return;
  if (!known) {
    throw InputError(spec.where,
                     fmt::format("contact '{}': no automatic penalty (no element with a Young's "
                                 "modulus behind its surfaces); give eps_n= and eps_t=",
                                 spec.name));
  }
  const double automatic = spec.penaltyScale * kAutomaticPenaltyFactor * stiffness;
  if (normal) config.law.penaltyNormal = automatic;
  if (tangential) config.law.penaltyTangential = automatic;
  config.automaticPenalty = true;
}

std::unique_ptr<contact::ContactPair> makePair(const ContactSpec& spec, const ProblemSpec& problem,
                                               const Mesh& mesh, const std::vector<bool>& active,
                                               const std::vector<double>& blockYoung) {
  const FaceSet& master = requireFaceSet(mesh, spec.master, spec.where, "master");
  requireAttached(master, active, spec.where);
  if (spec.kind != ContactSpec::Kind::SegmentToAnalytical) {
    requireFaceSet(mesh, spec.slave, spec.where, "slave");
  }
  contact::ContactPairConfig config = pairConfig(spec);
  setAutomaticPenalty(spec, mesh, blockYoung, config);
  if (spec.kind == ContactSpec::Kind::SegmentToAnalytical) {
    const auto rigid =
        std::find_if(problem.rigidSurfaces.begin(), problem.rigidSurfaces.end(),
                     [&](const RigidSurfaceSpec& r) { return r.name == spec.slave; });
    if (rigid == problem.rigidSurfaces.end()) {
      throw InputError(spec.where, fmt::format("contact stas: no rigid surface '{}'", spec.slave));
    }
    return contact::ContactPair::segmentToAnalytical(config, master, rigidSurface(*rigid),
                                                     surfaceMotion(*rigid));
  }
  if (config.smoothMaster && master.type != CellType::Quad4) {
    throw InputError(spec.where, fmt::format("contact '{}': surface=smooth needs a Quad4 "
                                             "master surface (Nagata patches over its corners)",
                                             spec.name));
  }
  const FaceSet& slave = requireFaceSet(mesh, spec.slave, spec.where, "slave");
  requireAttached(slave, active, spec.where);
  std::unique_ptr<contact::ContactPair> pair =
      spec.kind == ContactSpec::Kind::NodeToSegment
          ? contact::ContactPair::nodeToSegment(config, mesh, master, slave)
          : contact::ContactPair::segmentToSegment(config, master, slave);
  if (config.smoothMaster) pair->findCreases(mesh.coordinates);
  return pair;
}

}  // namespace

std::unique_ptr<Model> buildModel(const ProblemSpec& spec) {
  auto model = std::make_unique<Model>();
  model->spec_ = spec;
  model->mesh_ = loadMesh(spec.mesh);
  Mesh& mesh = model->mesh_;

  std::map<std::string, std::shared_ptr<const Material>> materials;
  for (const MaterialSpec& m : spec.materials) materials[m.name] = makeMaterial(m);

  std::set<int> usedBlocks;
  std::vector<bool> active(mesh.numNodes(), false);
  std::vector<double> blockYoung(mesh.blocks.size(), std::numeric_limits<double>::quiet_NaN());
  for (const ElementBlockSpec& blockSpec : spec.elementBlocks) {
    const int block = prepareBlock(mesh, blockSpec);
    if (!usedBlocks.insert(block).second) {
      throw InputError(blockSpec.where,
                       fmt::format("elements: group '{}' is already declared", blockSpec.group));
    }
    const ElementBlock& elements = mesh.blocks[block];
    blockYoung[block] = materials.at(blockSpec.material)->youngsModulus();
    for (Eigen::Index e = 0; e < elements.connectivity.rows(); ++e) {
      for (Eigen::Index k = 0; k < elements.connectivity.cols(); ++k)
        active[elements.connectivity(e, k)] = true;
    }
    model->elementSets_.push_back(std::make_unique<ElementSet>(
        blockSpec.group, elements, makeElementKernel(blockSpec), materials.at(blockSpec.material)));
  }

  // A physical volume without an `elements` line would be left out of the model together with
  // every load, support and contact on its nodes, without a word: refused (a volume meant to be
  // left out is removed from the .geo's physical groups).
  for (std::size_t block = 0; block < mesh.blocks.size(); ++block) {
    if (usedBlocks.count(static_cast<int>(block))) continue;
    throw InputError(spec.mesh.where,
                     fmt::format("the mesh's physical volume '{}' ({} elements) has no 'elements' "
                                 "line, so it and the loads and supports on it would be left out; "
                                 "add e.g. 'elements {} hex8 material=NAME', or remove the "
                                 "physical volume from the mesh",
                                 mesh.blocks[block].name, mesh.blocks[block].connectivity.rows(),
                                 mesh.blocks[block].name));
  }
  model->boundaryConditions_.build(spec, mesh);
  for (const ContactSpec& c : spec.contacts) {
    model->contactPairs_.push_back(makePair(c, spec, mesh, active, blockYoung));
  }

  model->dofs_ = DofMap(active, model->boundaryConditions_.constrainedDofs(mesh.numNodes()));
  std::vector<Contribution*> contributions;
  for (auto& set : model->elementSets_) contributions.push_back(set.get());
  for (auto& pair : model->contactPairs_) contributions.push_back(pair.get());
  model->assembler_ = std::make_unique<Assembler>(model->dofs_, contributions);

  auto addReactionSet = [&](const std::string& name) {
    if (std::find(model->reactionSets_.begin(), model->reactionSets_.end(), name) ==
        model->reactionSets_.end()) {
      model->reactionSets_.push_back(name);
    }
  };
  for (const FixSpec& f : spec.fixes) addReactionSet(f.set);
  for (const PrescribeSpec& p : spec.prescribed) addReactionSet(p.set);
  for (const LoadSpec& l : spec.loads) addReactionSet(l.set);
  return model;
}

}  // namespace cc
