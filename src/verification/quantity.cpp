// Reference quantities: "kind:name[:what][:component]" strings, checked against the model and
// measured on each converged step.
#include "verification/quantity.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "common/errors.hpp"

namespace cc::verification {

namespace {

constexpr const char* kAcceptedForms =
    "expected reaction:SET:x|y|z, displacement:SET:x|y|z, contact:PAIR:force:x|y|z or "
    "contact:PAIR:area|radius|half_width|stick_radius|stick_half_width|peak_pressure|"
    "centre_pressure|penetration|pressure_deviation|nodal_pressure_deviation|"
    "peak_nodal_pressure";

const std::map<std::string, Quantity::Kind>& contactScalars() {
  static const std::map<std::string, Quantity::Kind> scalars = {
      {"area", Quantity::Kind::ContactArea},
      {"radius", Quantity::Kind::ContactRadius},
      {"half_width", Quantity::Kind::ContactHalfWidth},
      {"stick_radius", Quantity::Kind::StickRadius},
      {"stick_half_width", Quantity::Kind::StickHalfWidth},
      {"peak_pressure", Quantity::Kind::PeakPressure},
      {"centre_pressure", Quantity::Kind::CentrePressure},
      {"penetration", Quantity::Kind::Penetration},
      {"pressure_deviation", Quantity::Kind::PressureDeviation},
      {"nodal_pressure_deviation", Quantity::Kind::NodalPressureDeviation},
      {"peak_nodal_pressure", Quantity::Kind::PeakNodalPressure}};
  return scalars;
}

std::vector<std::string> splitFields(const std::string& text) {
  std::vector<std::string> fields;
  std::stringstream stream(text);
  std::string field;
  while (std::getline(stream, field, ':')) fields.push_back(field);
  return fields;
}

int componentOf(const std::string& field) {
  if (field == "x") return 0;
  if (field == "y") return 1;
  if (field == "z") return 2;
  return -1;
}

// The face set on the slave side of pair `name` (nullptr for an STAS pair or a node set).
const FaceSet* slaveFaces(const Model& model, const std::string& name) {
  const ProblemSpec& spec = model.spec();
  for (std::size_t k = 0; k < spec.contacts.size(); ++k) {
    const ContactSpec& contact = spec.contacts[k];
    const std::string pairName = contact.name.empty() ? fmt::format("pair{}", k + 1) : contact.name;
    if (pairName != name || contact.kind == ContactSpec::Kind::SegmentToAnalytical) continue;
    const auto faces = model.mesh().faceSets.find(contact.slave);
    return faces == model.mesh().faceSets.end() ? nullptr : &faces->second;
  }
  return nullptr;
}

bool hasPair(const Model& model, const std::string& name) {
  return std::any_of(model.contactPairs().begin(), model.contactPairs().end(),
                     [&](const auto& pair) { return pair->name() == name; });
}

// Reactions are reported for the node sets that carry boundary conditions or loads.
bool hasReactionSet(const ProblemSpec& spec, const std::string& name) {
  auto named = [&](const auto& items) {
    return std::any_of(items.begin(), items.end(),
                       [&](const auto& item) { return item.set == name; });
  };
  return named(spec.fixes) || named(spec.prescribed) || named(spec.loads);
}

Quantity parseFields(const std::vector<std::string>& fields, const SourceLocation& where) {
  auto fail = [&](const std::string& why) { throw InputError(where, why); };
  Quantity q;
  if (fields.size() < 3) fail(kAcceptedForms);
  q.name = fields[1];
  if (fields[0] == "reaction" || fields[0] == "displacement") {
    q.kind = fields[0] == "reaction" ? Quantity::Kind::Reaction : Quantity::Kind::Displacement;
    q.component = componentOf(fields[2]);
    if (fields.size() != 3 || q.component < 0) fail(kAcceptedForms);
  } else if (fields[0] == "contact" && fields[2] == "force") {
    q.kind = Quantity::Kind::ContactForce;
    if (fields.size() != 4 || (q.component = componentOf(fields[3])) < 0) fail(kAcceptedForms);
  } else if (fields[0] == "contact" && fields.size() == 3 && contactScalars().contains(fields[2])) {
    q.kind = contactScalars().at(fields[2]);
  } else {
    fail(kAcceptedForms);
  }
  return q;
}

}  // namespace

Quantity parseQuantity(const std::string& text, const Model& model, const SourceLocation& where) {
  Quantity q = parseFields(splitFields(text), where);
  q.text = text;
  const bool isContact =
      q.kind != Quantity::Kind::Reaction && q.kind != Quantity::Kind::Displacement;
  if (isContact && !hasPair(model, q.name)) {
    throw InputError(where, fmt::format("no contact pair named '{}' in this deck", q.name));
  }
  if (q.kind == Quantity::Kind::NodalPressureDeviation ||
      q.kind == Quantity::Kind::PeakNodalPressure) {
    const FaceSet* faces = slaveFaces(model, q.name);
    if (!faces) {
      throw InputError(where, fmt::format("{} needs a slave face set; pair '{}' has none (stas, "
                                          "or nts on a node set)",
                                          splitFields(text).back(), q.name));
    }
    q.slaveAreas =
        std::make_shared<const std::map<int, double>>(tributaryAreas(model.mesh(), *faces));
  }
  if (q.kind == Quantity::Kind::Reaction && !hasReactionSet(model.spec(), q.name)) {
    throw InputError(where, fmt::format("no reaction is reported for '{}': name a node set that "
                                        "has a fix, prescribe or load line",
                                        q.name));
  }
  if (q.kind == Quantity::Kind::Displacement && !model.mesh().nodeSets.contains(q.name)) {
    throw InputError(where, fmt::format("no node set named '{}' in the mesh", q.name));
  }
  return q;
}

const ContactPairRecord& pairRecord(const StepRecord& step, const std::string& name) {
  for (const ContactPairRecord& pair : step.contact) {
    if (pair.name == name) return pair;
  }
  throw std::out_of_range("no contact pair " + name + " in the step record");
}

double measure(const Quantity& quantity, const StepRecord& step, const Mesh& mesh,
               const ModelledPart& part) {
  using Kind = Quantity::Kind;
  switch (quantity.kind) {
    case Kind::Reaction:
      for (const auto& [set, force] : step.setReactions) {
        if (set == quantity.name) return force[quantity.component];
      }
      throw std::out_of_range("no reaction for set " + quantity.name);
    case Kind::Displacement: {
      const std::vector<int>& nodes = mesh.nodeSets.at(quantity.name).nodes;
      double sum = 0;
      for (int node : nodes) sum += (*step.displacement)(quantity.component, node);
      return sum / static_cast<double>(nodes.size());
    }
    default:
      break;
  }
  const ContactPairRecord& pair = pairRecord(step, quantity.name);
  switch (quantity.kind) {
    case Kind::ContactForce:
      return pair.totalForce[quantity.component];
    case Kind::ContactArea:
      return contactArea(pair) / part.fraction;
    case Kind::ContactRadius:
      return equivalentRadius(contactArea(pair), part);
    case Kind::ContactHalfWidth:
      return equivalentHalfWidth(contactArea(pair), part);
    case Kind::StickRadius:
      return equivalentRadius(stickArea(pair), part);
    case Kind::StickHalfWidth:
      return equivalentHalfWidth(stickArea(pair), part);
    case Kind::PeakPressure:
      return peakPressure(pair);
    case Kind::CentrePressure:
      return centrePressure(pair, part);
    case Kind::Penetration:
      return maxPenetration(pair);
    case Kind::PressureDeviation:
      return pressureDeviation(pair);
    case Kind::NodalPressureDeviation:
      return nodalPressureDeviation(pair, *quantity.slaveAreas);
    case Kind::PeakNodalPressure:
      return peakNodalPressure(pair, *quantity.slaveAreas);
    default:
      break;
  }
  throw std::logic_error("unhandled quantity kind");
}

}  // namespace cc::verification
