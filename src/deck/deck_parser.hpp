// Public interface of the deck parser: deck file (+ includes) -> validated ProblemSpec, and the
// keyword reference generated from the keyword declarations. Language: input/README.md.
#pragma once

#include <string>

#include "spec/problem_spec.hpp"

namespace cc {

// Reads the deck at `path` and every file it includes. Throws InputError ("file:line:col:
// error: what was expected") for any problem the deck itself shows; mesh-dependent checks
// (sets, groups, expressions) are left to the model builder.
ProblemSpec parseDeck(const std::string& path);

// As parseDeck for text already in memory; `virtualPath` names it in messages and includes
// are resolved relative to its directory.
ProblemSpec parseDeckText(const std::string& text, const std::string& virtualPath);

// The keyword reference in Markdown (the generated part of input/README.md).
std::string keywordReferenceMarkdown();

// A short plain-text listing of every keyword and parameter (`covcontact check --keywords`).
std::string keywordListing();

}  // namespace cc
