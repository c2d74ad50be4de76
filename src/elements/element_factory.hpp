// Creates the element kernel a deck `elements` line asks for.
#pragma once

#include <memory>

#include "elements/element.hpp"
#include "spec/problem_spec.hpp"

namespace cc {

std::unique_ptr<ElementKernel> makeElementKernel(const ElementBlockSpec& spec);
const char* elementTypeName(ElementBlockSpec::Type type);

}  // namespace cc
