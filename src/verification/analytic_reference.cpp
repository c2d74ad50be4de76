// Analytic references: parameter checking, the loads and probe approaches measured on a step, and
// the Hertz / Cattaneo-Mindlin values they imply. Conventions (documented in
// docs/verification/accuracy.md): the load acts along global z, cylinder axes are along global y,
// body 1 (the indenter) lies above the contact plane z = z0 and body 2 below it.
#include "verification/analytic_reference.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "common/errors.hpp"
#include "model/time_function.hpp"
#include "verification/analytic_contact.hpp"

namespace cc::verification {

namespace {

constexpr double kRigid = std::numeric_limits<double>::infinity();
// A probe must be a mesh node: the nearest node may be off by round-off of the mesh generator.
constexpr double kProbeTolerance = 1e-6;  // relative to the mesh's bounding-box diagonal
// Cattaneo-Mindlin's uncoupled solution holds for Dundurs beta = 0 (elastically similar bodies).
constexpr double kMaxDundursBeta = 1e-9;
constexpr int kZ = 2;

const std::vector<std::string> kSphereParameters = {
    "R", "E", "nu", "E1", "nu1", "fraction", "x0", "y0", "z0", "probe1_z", "probe2_z"};
const std::vector<std::string> kCylinderParameters = {"R",   "E",        "nu",     "E1",
                                                      "nu1", "fraction", "length", "x0"};

// The deck's NAME=NUMBER parameters of one analytic reference; unknown names are errors.
class Parameters {
 public:
  Parameters(const ReferenceSpec& spec, const std::vector<std::string>& allowed) : spec_(spec) {
    for (const auto& [name, value] : spec.parameters) {
      if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
        fail(fmt::format("unknown parameter '{}' of {}; it accepts {}", name, spec.analytic,
                         fmt::join(allowed, ", ")));
      }
    }
  }
  bool has(const std::string& name) const { return spec_.parameters.contains(name); }
  double optional(const std::string& name, double fallback) const {
    return has(name) ? spec_.parameters.at(name) : fallback;
  }
  double required(const std::string& name) const {
    if (!has(name)) fail(fmt::format("{} needs the parameter {}=NUMBER", spec_.analytic, name));
    return spec_.parameters.at(name);
  }
  double positive(const std::string& name) const {
    const double value = required(name);
    if (!(value > 0)) fail(fmt::format("{} must be > 0, got {}", name, value));
    return value;
  }
  [[noreturn]] void fail(const std::string& message) const {
    throw InputError(spec_.where, message);
  }

 private:
  const ReferenceSpec& spec_;
};

// E, nu: the body below the contact plane; E1, nu1: the indenter (rigid when E1 is not given).
ElasticPair elasticPair(const Parameters& p) {
  ElasticPair pair{kRigid, 0, p.positive("E"), p.required("nu")};
  if (p.has("E1")) {
    pair.youngs1 = p.positive("E1");
    pair.poisson1 = p.required("nu1");
  }
  for (double poisson : {pair.poisson1, pair.poisson2}) {
    if (!(poisson > -1 && poisson < 0.5))
      p.fail(fmt::format("nu must be in (-1, 0.5), got {}", poisson));
  }
  return pair;
}

ModelledPart modelledPart(const Parameters& p, bool plane) {
  ModelledPart part{p.optional("fraction", 1), plane ? p.optional("length", 1) : 1, plane,
                    p.optional("x0", 0), plane ? 0 : p.optional("y0", 0)};
  if (!(part.fraction > 0 && part.fraction <= 1)) p.fail("fraction must be in (0, 1]");
  if (!(part.length > 0)) p.fail("length must be > 0");
  return part;
}

// The full contact's loads from a pair's total force: per unit length for plane strain.
struct MeasuredLoads {
  std::string pair;
  double scale;  // 1 / (fraction * length)

  double component(const StepRecord& step, int c) const {
    return std::abs(pairRecord(step, pair).totalForce[c]) * scale;
  }
  double normal(const StepRecord& step) const { return component(step, kZ); }
  double tangential(const StepRecord& step) const {
    return pairRecord(step, pair).totalForce.head<2>().norm() * scale;
  }
};

// Relative displacement of two points on the contact axis, one in each body: a mesh node, or for
// a rigid indenter (STAS) the translation of its surface.
class AxisProbes {
 public:
  AxisProbes(const Parameters& p, const std::string& pairName, const Model& model) {
    const Eigen::Vector3d axis(p.optional("x0", 0), p.optional("y0", 0), p.optional("z0", 0));
    node2_ = nodeAt(p, model.mesh(), axis, p.required("probe2_z"));
    depth2_ = std::abs(p.required("probe2_z") - axis.z());
    if (p.has("probe1_z")) {
      node1_ = nodeAt(p, model.mesh(), axis, p.required("probe1_z"));
      depth1_ = std::abs(p.required("probe1_z") - axis.z());
      return;
    }
    const RigidSurfaceSpec* rigid = rigidIndenter(model.spec(), pairName);
    if (!rigid) p.fail("give probe1_z (a node on the axis in the upper body) or use an stas pair");
    for (int c = 0; c < 3; ++c) {
      if (rigid->motion[c])
        motion_[c] = std::shared_ptr<ScalarFunction>(makeFunction(*rigid->motion[c]));
    }
  }

  // Displacement of body 1's probe minus body 2's, component c.
  double relative(const StepRecord& step, int c) const {
    const double lower = (*step.displacement)(c, node2_);
    if (node1_ >= 0) return (*step.displacement)(c, node1_) - lower;
    const double upper = motion_[c] ? (*motion_[c])(step.time) - (*motion_[c])(0) : 0;
    return upper - lower;
  }
  double depth1() const { return depth1_; }
  double depth2() const { return depth2_; }

 private:
  static int nodeAt(const Parameters& p, const Mesh& mesh, const Eigen::Vector3d& axis, double z) {
    const Eigen::Vector3d target(axis.x(), axis.y(), z);
    Eigen::Index nearest = 0;
    const double distance =
        (mesh.coordinates.colwise() - target).colwise().norm().minCoeff(&nearest);
    const Eigen::Vector3d diagonal =
        mesh.coordinates.rowwise().maxCoeff() - mesh.coordinates.rowwise().minCoeff();
    if (distance > kProbeTolerance * diagonal.norm()) {
      p.fail(fmt::format("no mesh node at the probe point ({}, {}, {}); the nearest is {:.3g} away",
                         target.x(), target.y(), target.z(), distance));
    }
    return static_cast<int>(nearest);
  }
  static const RigidSurfaceSpec* rigidIndenter(const ProblemSpec& spec, const std::string& pair) {
    for (std::size_t k = 0; k < spec.contacts.size(); ++k) {
      const ContactSpec& contact = spec.contacts[k];
      const std::string name = contact.name.empty() ? fmt::format("pair{}", k + 1) : contact.name;
      if (name != pair || contact.kind != ContactSpec::Kind::SegmentToAnalytical) continue;
      for (const RigidSurfaceSpec& rigid : spec.rigidSurfaces) {
        if (rigid.name == contact.slave) return &rigid;
      }
    }
    return nullptr;
  }

  int node1_ = -1, node2_ = -1;
  double depth1_ = 0, depth2_ = 0;
  std::array<std::shared_ptr<ScalarFunction>, 3> motion_;
};

using Kind = Quantity::Kind;

std::optional<double> ifLoaded(double load, double value) {
  return load > 0 ? std::optional<double>(value) : std::nullopt;
}

[[noreturn]] void unsupported(const Parameters& p, const ReferenceSpec& spec,
                              const char* accepted) {
  p.fail(fmt::format("{} gives no value for '{}'; it gives {}", spec.analytic, spec.quantity,
                     accepted));
}

AnalyticComparison sphereComparison(const ReferenceSpec& spec, const Quantity& q,
                                    const Model& model, bool mindlin) {
  std::vector<std::string> allowed = kSphereParameters;
  if (mindlin) allowed.push_back("mu");
  const Parameters p(spec, allowed);
  const ModelledPart part = modelledPart(p, false);
  const HertzSphere hertz{p.positive("R"), elasticPair(p)};
  const MeasuredLoads loads{q.name, 1 / part.fraction};
  AnalyticComparison c;
  c.measured = [q, part, &mesh = model.mesh()](const StepRecord& s) {
    return measure(q, s, mesh, part);
  };
  if (q.kind == Kind::ContactRadius) {
    c.reference = [=](const StepRecord& s) {
      return ifLoaded(loads.normal(s), hertz.contactRadius(loads.normal(s)));
    };
  } else if (q.kind == Kind::PeakPressure || q.kind == Kind::CentrePressure ||
             q.kind == Kind::PeakNodalPressure) {
    c.reference = [=](const StepRecord& s) {
      return ifLoaded(loads.normal(s), hertz.peakPressure(loads.normal(s)));
    };
  } else if (q.kind == Kind::ContactForce && q.component == kZ) {
    const auto probes = std::make_shared<AxisProbes>(p, q.name, model);
    c.measured = [=](const StepRecord& s) { return loads.normal(s); };
    c.reference = [=](const StepRecord& s) {
      const double approach = -probes->relative(s, kZ);
      return ifLoaded(approach,
                      hertz.loadAtProbeApproach(approach, probes->depth1(), probes->depth2()));
    };
  } else if (!mindlin) {
    unsupported(p, spec,
                "contact:PAIR:force:z (at the probes' approach), radius, peak_pressure, "
                "peak_nodal_pressure, centre_pressure");
  }
  if (!mindlin || c.reference) return c;

  const CattaneoMindlinSphere cm{hertz, p.positive("mu")};
  if (std::abs(hertz.bodies.dundursBeta()) > kMaxDundursBeta) {
    p.fail(
        fmt::format("cattaneo_mindlin_sphere needs elastically similar bodies (Dundurs beta = 0, "
                    "e.g. E1 = E, nu1 = nu); these give beta = {:.3g}",
                    hertz.bodies.dundursBeta()));
  }
  if (q.kind == Kind::StickRadius) {
    c.reference = [=](const StepRecord& s) {
      const double load = loads.normal(s);
      const double ratio = std::min(loads.tangential(s) / (cm.friction * load), 1.0);
      return ifLoaded(load, cm.stickRadius(load, ratio * cm.friction * load));
    };
  } else if (q.kind == Kind::ContactForce) {
    const auto probes = std::make_shared<AxisProbes>(p, q.name, model);
    const int component = q.component;
    c.measured = [=](const StepRecord& s) { return loads.component(s, component); };
    c.reference = [=](const StepRecord& s) {
      const double load = loads.normal(s);
      const double approach = std::abs(probes->relative(s, component));
      return ifLoaded(load, cm.tangentialLoadAtProbeApproach(load, approach, probes->depth1(),
                                                             probes->depth2()));
    };
  } else {
    unsupported(p, spec,
                "contact:PAIR:force:x|y (at the probes' tangential approach), force:z, radius, "
                "peak_pressure, peak_nodal_pressure, centre_pressure, stick_radius");
  }
  return c;
}

AnalyticComparison cylinderComparison(const ReferenceSpec& spec, const Quantity& q,
                                      const Model& model, bool mindlin) {
  std::vector<std::string> allowed = kCylinderParameters;
  if (mindlin) allowed.push_back("mu");
  const Parameters p(spec, allowed);
  const ModelledPart part = modelledPart(p, true);
  const HertzCylinder hertz{p.positive("R"), elasticPair(p)};
  const MeasuredLoads loads{q.name, 1 / (part.fraction * part.length)};
  AnalyticComparison c;
  c.measured = [q, part, &mesh = model.mesh()](const StepRecord& s) {
    return measure(q, s, mesh, part);
  };
  if (q.kind == Kind::ContactHalfWidth) {
    c.reference = [=](const StepRecord& s) {
      return ifLoaded(loads.normal(s), hertz.halfWidth(loads.normal(s)));
    };
  } else if (q.kind == Kind::PeakPressure || q.kind == Kind::CentrePressure ||
             q.kind == Kind::PeakNodalPressure) {
    c.reference = [=](const StepRecord& s) {
      return ifLoaded(loads.normal(s), hertz.peakPressure(loads.normal(s)));
    };
  } else if (mindlin && q.kind == Kind::StickHalfWidth) {
    const CattaneoMindlinCylinder cm{hertz, p.positive("mu")};
    if (std::abs(hertz.bodies.dundursBeta()) > kMaxDundursBeta) {
      p.fail(
          fmt::format("cattaneo_mindlin_cylinder needs elastically similar bodies (Dundurs "
                      "beta = 0); these give beta = {:.3g}",
                      hertz.bodies.dundursBeta()));
    }
    c.reference = [=](const StepRecord& s) {
      const double load = loads.normal(s);
      const double tangential = std::min(loads.tangential(s), cm.friction * load);
      return ifLoaded(load, cm.stickHalfWidth(load, tangential));
    };
  } else {
    unsupported(p, spec,
                mindlin ? "half_width, peak_pressure, peak_nodal_pressure, centre_pressure, "
                          "stick_half_width"
                        : "half_width, peak_pressure, peak_nodal_pressure, centre_pressure");
  }
  return c;
}

}  // namespace

std::vector<std::string> analyticSolutionNames() {
  return {"hertz_sphere", "hertz_cylinder", "cattaneo_mindlin_sphere", "cattaneo_mindlin_cylinder"};
}

AnalyticComparison makeAnalyticComparison(const ReferenceSpec& spec, const Quantity& quantity,
                                          const Model& model) {
  const bool contactQuantity =
      quantity.kind != Kind::Reaction && quantity.kind != Kind::Displacement;
  if (spec.analytic == "hertz_sphere" || spec.analytic == "cattaneo_mindlin_sphere" ||
      spec.analytic == "hertz_cylinder" || spec.analytic == "cattaneo_mindlin_cylinder") {
    if (!contactQuantity) {
      throw InputError(spec.where, fmt::format("{} compares contact quantities "
                                               "(contact:PAIR:...), not '{}'",
                                               spec.analytic, spec.quantity));
    }
  }
  if (spec.analytic == "hertz_sphere") return sphereComparison(spec, quantity, model, false);
  if (spec.analytic == "cattaneo_mindlin_sphere")
    return sphereComparison(spec, quantity, model, true);
  if (spec.analytic == "hertz_cylinder") return cylinderComparison(spec, quantity, model, false);
  if (spec.analytic == "cattaneo_mindlin_cylinder")
    return cylinderComparison(spec, quantity, model, true);
  throw InputError(spec.where,
                   fmt::format("unknown analytic solution '{}'; expected one of {}", spec.analytic,
                               fmt::join(analyticSolutionNames(), ", ")));
}

}  // namespace cc::verification
