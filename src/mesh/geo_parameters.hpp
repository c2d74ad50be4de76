// Which parameters a gmsh .geo file lets the deck set: the names declared in its
// DefineConstant[...] lists (and those of the files it Includes), so that a misspelt mesh
// parameter in a deck is an error instead of being silently ignored by gmsh.
#pragma once

#include <set>
#include <string>

namespace cc {

// Names declared by DefineConstant[ name = ..., ... ] in `geoPath` and, recursively, in files it
// includes with Include "file"; (paths relative to the including file). Comments and string
// literals are skipped. Unreadable files contribute no names.
std::set<std::string> geoDefinedConstants(const std::string& geoPath);

}  // namespace cc
