// Gauss-point stress access of the solid-shell elements behind the ElementKernel interface.
#include <stdexcept>

#include "elements/solid_shell.hpp"
#include "elements/solid_shell_element.hpp"

namespace cc {

ElementStatus solidShellGaussPointStresses(const ElementKernel& element, const Eigen::Matrix3Xd& X,
                                           const Eigen::Matrix3Xd& x, const Material& material,
                                           std::vector<GaussPointStress>& stresses) {
  if (const auto* shell8 = dynamic_cast<const solidshell::SolidShell8Element*>(&element)) {
    return shell8->gaussPointStresses(X, x, material, stresses);
  }
  if (const auto* shell18 = dynamic_cast<const solidshell::SolidShell18Element*>(&element)) {
    return shell18->gaussPointStresses(X, x, material, stresses);
  }
  throw std::invalid_argument("solidShellGaussPointStresses: " + element.name() +
                              " is not a solid-shell element");
}

}  // namespace cc
