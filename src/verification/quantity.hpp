// The result quantities a deck's `reference` line can name (e.g. "contact:pair1:force:z"), their
// parsing and validation against the model, and their measurement on a converged step.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "common/source_location.hpp"
#include "model/model.hpp"
#include "records/result_records.hpp"
#include "verification/contact_measures.hpp"

namespace cc::verification {

struct Quantity {
  enum class Kind {
    Reaction,                // reaction:SET:x|y|z       summed reaction of a node set
    Displacement,            // displacement:SET:x|y|z   mean displacement of a node set
    ContactForce,            // contact:PAIR:force:x|y|z total contact force (on the slave side)
    ContactArea,             // contact:PAIR:area        area of the points in contact
    ContactRadius,           // contact:PAIR:radius      radius of the equal-area disk
    ContactHalfWidth,        // contact:PAIR:half_width  half-width of the equal-area strip
    StickRadius,             // contact:PAIR:stick_radius      the same for the stick points
    StickHalfWidth,          // contact:PAIR:stick_half_width
    PeakPressure,            // contact:PAIR:peak_pressure     max -N
    CentrePressure,          // contact:PAIR:centre_pressure   -N nearest to the load axis
    Penetration,             // contact:PAIR:penetration       max -g
    PressureDeviation,       // contact:PAIR:pressure_deviation  max |p - mean| / mean
    NodalPressureDeviation,  // contact:PAIR:nodal_pressure_deviation  the same for |f_a| / A_a
    PeakNodalPressure,       // contact:PAIR:peak_nodal_pressure  max |f_a| / A_a over slave nodes
  };
  Kind kind = Kind::Reaction;
  std::string name;    // node set or contact pair
  int component = -1;  // 0, 1, 2 for x, y, z; -1 for scalars
  std::string text;    // as written in the deck
  // NodalPressureDeviation, PeakNodalPressure: tributary areas of the pair's slave face set.
  std::shared_ptr<const std::map<int, double>> slaveAreas;
};

// Parses and checks that the set or pair exists in the model; throws InputError at `where`
// listing the accepted forms.
Quantity parseQuantity(const std::string& text, const Model& model, const SourceLocation& where);

// The quantity's value on a converged step. Areas, radii and half-widths are of the full contact
// (`part` says how much of it the model holds and where its load axis is).
double measure(const Quantity& quantity, const StepRecord& step, const Mesh& mesh,
               const ModelledPart& part = {});

// The record of contact pair `name` in `step` (throws std::out_of_range if absent).
const ContactPairRecord& pairRecord(const StepRecord& step, const std::string& name);

}  // namespace cc::verification
