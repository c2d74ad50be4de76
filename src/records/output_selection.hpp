// OutputSelection: which fields and sidecar files the results writer produces. Filled by the model
// from the deck's `output` block, read by the writer; plain data so neither includes the other.
#pragma once

namespace cc {

// Which fields and sidecars to write (the model fills it from the deck's `output` block).
struct OutputSelection {
  bool displacement = true;
  bool reaction = true;
  bool stress = false;
  bool contact = true;
  bool csv = true;   // <stem>_reactions.csv
  bool xdmf = true;  // <stem>.xdmf
};

}  // namespace cc
