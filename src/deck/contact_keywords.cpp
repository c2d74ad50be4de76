// Handlers of the contact keywords: rigid analytic surfaces (with their per-shape parameters)
// and contact pairs (kind, surfaces, penalties, friction, tangent parts).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/errors.hpp"
#include "common/name_matching.hpp"
#include "deck/deck_state.hpp"
#include "deck/spec_choices.hpp"

namespace cc::deck {

namespace {

using Shape = RigidSurfaceSpec::Shape;

// Parameters each rigid shape needs (origin is optional for all of them).
const std::vector<std::string>& requiredShapeParameters(Shape shape) {
  static const std::vector<std::string> plane = {"normal"};
  static const std::vector<std::string> cylinder = {"axis", "radius"};
  static const std::vector<std::string> parabolicCylinder = {"normal", "axis", "c"};
  static const std::vector<std::string> sphere = {"radius"};
  switch (shape) {
    case Shape::Plane:
      return plane;
    case Shape::Cylinder:
      return cylinder;
    case Shape::ParabolicCylinder:
      return parabolicCylinder;
    case Shape::Sphere:
      return sphere;
  }
  return plane;
}

double norm(const Vec3& v) {
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// sin of the angle below which the opening direction and the axis of a parabolic cylinder
// count as parallel (the local frame would be undefined).
constexpr double kParallelSine = 1e-8;

void checkShapeParameters(const ParsedLine& line, Shape shape) {
  const std::string& shapeName = line.positional(1).text;
  const std::vector<std::string>& required = requiredShapeParameters(shape);
  for (const char* name : {"normal", "axis", "radius", "c"}) {
    const bool needed = std::find(required.begin(), required.end(), name) != required.end();
    if (line.given(name) && !needed) {
      line.fail(line.value(name).where,
                fmt::format("{}= does not apply to a {} surface", name, shapeName));
    }
    if (!line.given(name) && needed) {
      line.fail(line.end(), fmt::format("a {} surface needs {}= ({})", shapeName, name,
                                        line.keyword().findParameter(name)->description));
    }
  }
  for (const char* direction : {"normal", "axis"}) {
    if (line.given(direction) && norm(line.value(direction).vector) == 0) {
      line.fail(line.value(direction).where,
                fmt::format("{} must not be the zero vector", direction));
    }
  }
  if (shape != Shape::ParabolicCylinder) return;
  if (line.number("c") == 0) {
    line.fail(line.value("c").where, "c must be non-zero (c = 0 is a plane: use 'plane')");
  }
  const Vec3& normal = line.value("normal").vector;
  const Vec3& axis = line.value("axis").vector;
  if (norm(cross(normal, axis)) <= kParallelSine * norm(normal) * norm(axis)) {
    line.fail(line.value("axis").where, "axis must not be parallel to normal");
  }
}

}  // namespace

void handleRigid(const ParsedLine& line, DeckState& state) {
  const Value& name = line.positional(0);
  for (const RigidSurfaceSpec& earlier : state.spec.rigidSurfaces) {
    if (earlier.name == name.text) {
      line.fail(name.where, fmt::format("duplicate rigid surface '{}' (first defined at {})",
                                        name.text, earlier.where.str()));
    }
  }
  RigidSurfaceSpec rigid;
  rigid.name = name.text;
  rigid.shape = choiceValue(rigidShapes(), line.positional(1).text);
  checkShapeParameters(line, rigid.shape);
  rigid.origin = line.value("origin").vector;
  if (line.given("normal")) rigid.normal = line.value("normal").vector;
  if (line.given("axis")) rigid.axis = line.value("axis").vector;
  if (line.given("radius")) rigid.radius = line.number("radius");
  if (line.given("c")) rigid.curvature = line.number("c");
  for (std::size_t i = 0; i < kDisplacementComponents.size(); ++i) {
    if (const Clause* clause = line.findClause(kDisplacementComponents[i])) {
      rigid.motion[i] = clause->function;
    }
  }
  rigid.where = line.where();
  state.spec.rigidSurfaces.push_back(rigid);
}

namespace {

void setTangentParts(const ParsedLine& line, const std::string& context, ContactSpec& contact) {
  if (line.given("tangent") && line.given("parts")) {
    throw InputError(line.value("parts").where,
                     context + ": give either tangent= or parts=, not both");
  }
  if (line.given("parts")) {
    contact.tangentMode = ContactSpec::TangentMode::Paper;
    for (const auto& [name, field] : tangentParts()) contact.parts.*field = false;
    for (const std::string& name : line.value("parts").list) {
      contact.parts.*choiceValue(tangentParts(), name) = true;
    }
    return;
  }
  const TangentPreset preset = choiceValue(tangentPresets(), line.text("tangent"));
  contact.tangentMode = preset.mode;
  contact.parts = preset.parts;
}

}  // namespace

namespace {

// A contact line's errors name the pair, also when its name is the default one.
struct PairLine {
  const ParsedLine& line;
  std::string context;  // "contact 'NAME'"
  [[noreturn]] void fail(const SourceLocation& where, const std::string& message) const {
    throw InputError(where, context + ": " + message);
  }
  // A parameter given where `applies` is false fails with `why`.
  void refuseUnless(bool applies, const char* name, const std::string& why) const {
    if (!applies && line.given(name)) fail(line.value(name).where, why);
  }
};

// The pair's name (unique in the deck) and its two surfaces (different ones).
void setPairSurfaces(const PairLine& pair, const DeckState& state, ContactSpec& contact) {
  const ParsedLine& line = pair.line;
  for (const ContactSpec& earlier : state.spec.contacts) {
    if (earlier.name == contact.name) {
      pair.fail(line.given("name") ? line.value("name").where : line.where(),
                fmt::format("duplicate contact pair name '{}' (first at {})", contact.name,
                            earlier.where.str()));
    }
  }
  contact.master = line.text("master");
  contact.slave = line.text("slave");
  if (contact.master == contact.slave) {
    pair.fail(line.value("slave").where,
              fmt::format("master and slave are both '{}'; a pair needs two different surfaces",
                          contact.slave));
  }
}

// Penalties, friction and the enforcement (penalty or augmented Lagrangian) with its options.
void setEnforcement(const PairLine& pair, ContactSpec& contact) {
  const ParsedLine& line = pair.line;
  // An omitted eps_n (eps_t when mu > 0) is chosen from the adjacent elements' stiffness when
  // the model is built (model/automatic_penalty.cpp); 0 marks it as automatic.
  if (line.given("eps_n")) contact.penaltyNormal = line.number("eps_n");
  contact.friction = line.number("mu");
  if (line.given("eps_t")) contact.penaltyTangential = line.number("eps_t");
  const bool automatic = !line.given("eps_n") || (contact.friction > 0 && !line.given("eps_t"));
  pair.refuseUnless(
      automatic, "eps_scale",
      "eps_scale= scales the automatic penalty, but eps_n= and eps_t= are both given");
  contact.penaltyScale = line.number("eps_scale");
  contact.enforcement = choiceValue(contactEnforcements(), line.text("enforcement"));
  const bool augmented = contact.enforcement != ContactSpec::Enforcement::Penalty;
  for (const char* name : {"aug_tol", "aug_max", "aug_depth", "aug_grow"}) {
    pair.refuseUnless(augmented, name,
                      fmt::format("{}= applies to enforcement=augmented only", name));
  }
  contact.augmentationTolerance = line.number("aug_tol");
  contact.maxAugmentations = line.integer("aug_max");
  contact.accelerationDepth = line.integer("aug_depth");
  contact.growPenalty = line.flag("aug_grow");
}

// How the pair's points and master surface are discretised: the options each kind takes.
void setDiscretisation(const PairLine& pair, ContactSpec& contact) {
  const ParsedLine& line = pair.line;
  const bool nts = contact.kind == ContactSpec::Kind::NodeToSegment;
  const bool stas = contact.kind == ContactSpec::Kind::SegmentToAnalytical;
  pair.refuseUnless(!nts, "points",
                    "points= applies to sts and stas pairs only (nts uses the slave nodes)");
  contact.integrationPoints = line.integer("points");
  setTangentParts(line, pair.context, contact);
  contact.masterSurface = choiceValue(masterSurfaces(), line.text("surface"));
  const bool smooth = contact.masterSurface == ContactSpec::MasterSurface::Smooth;
  pair.refuseUnless(!(stas && smooth), "surface",
                    "surface=smooth applies to sts and nts pairs only (stas integrates on the "
                    "master's own segments)");
  contact.creaseDegrees = line.number("crease");
  pair.refuseUnless(smooth, "crease",
                    "crease= applies to surface=smooth only (a faceted master keeps every edge "
                    "as meshed)");
  contact.masterEdge = choiceValue(masterEdges(), line.text("edge"));
  pair.refuseUnless(!stas, "edge", "edge= applies to sts and nts pairs only");
  contact.integration = choiceValue(contactIntegrations(), line.text("integration"));
  pair.refuseUnless(contact.kind == ContactSpec::Kind::SegmentToSegment, "integration",
                    "integration= applies to sts pairs only (nts uses the slave nodes, stas the "
                    "master's Gauss points against the rigid surface)");
}

}  // namespace

void handleContact(const ParsedLine& line, DeckState& state) {
  ContactSpec contact;
  contact.kind = choiceValue(contactKinds(), line.positional(0).text);
  contact.name = line.given("name") ? line.text("name")
                                    : fmt::format("pair{}", state.spec.contacts.size() + 1);
  const PairLine pair{line, fmt::format("contact '{}'", contact.name)};
  setPairSurfaces(pair, state, contact);
  setEnforcement(pair, contact);
  setDiscretisation(pair, contact);
  contact.where = line.where();
  // The surfaces' names are checked against the mesh and the rigid surfaces after the deck.
  const std::string& kindName = line.positional(0).text;
  state.faceSetUses.push_back(
      {contact.master, line.value("master").where, pair.context, "master", kindName});
  const NameUse slave{contact.slave, line.value("slave").where, pair.context, "slave", kindName};
  if (contact.kind == ContactSpec::Kind::SegmentToAnalytical) {
    state.rigidUses.push_back(slave);
  } else {
    state.faceSetUses.push_back(slave);
  }
  state.spec.contacts.push_back(contact);
}

}  // namespace cc::deck
