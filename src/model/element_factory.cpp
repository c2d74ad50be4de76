// Element kernel factory: deck element type -> ElementKernel.
#include "model/element_factory.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "common/errors.hpp"
#include "elements/solid_shell.hpp"

namespace cc {

const char* elementTypeName(ElementBlockSpec::Type type) {
  switch (type) {
    case ElementBlockSpec::Type::Hex8:
      return "hex8";
    case ElementBlockSpec::Type::SolidShell8:
      return "solid_shell8";
    case ElementBlockSpec::Type::SolidShell18:
      return "solid_shell18";
  }
  return "?";
}

std::unique_ptr<ElementKernel> makeElementKernel(const ElementBlockSpec& spec) {
  switch (spec.type) {
    case ElementBlockSpec::Type::Hex8:
      return makeHex8();
    case ElementBlockSpec::Type::SolidShell8:
    case ElementBlockSpec::Type::SolidShell18:
      try {  // the solid-shell factories reject unsupported EAS parameter counts
        return spec.type == ElementBlockSpec::Type::SolidShell8
                   ? makeSolidShell8(spec.easParameters)
                   : makeSolidShell18(spec.easParameters);
      } catch (const std::invalid_argument& error) {
        throw InputError(spec.where, fmt::format("elements '{}': {}", spec.group, error.what()));
      }
  }
  throw InputError(spec.where, fmt::format("elements: {} is not available in this build",
                                           elementTypeName(spec.type)));
}

}  // namespace cc
