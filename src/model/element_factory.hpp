// Creates the element kernel a deck `elements` line asks for: the spec-to-runtime translation of
// element blocks, beside the rest of it in the model builder.
#pragma once

#include <memory>

#include "elements/element.hpp"
#include "spec/problem_spec.hpp"

namespace cc {

std::unique_ptr<ElementKernel> makeElementKernel(const ElementBlockSpec& spec);
const char* elementTypeName(ElementBlockSpec::Type type);

}  // namespace cc
