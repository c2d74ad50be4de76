// Element status messages of the shared total-Lagrangian kinematics (failure path only).
#include "elements/kinematics_common.hpp"

#include <sstream>

namespace cc::tl {

ElementStatus invertedJacobian(const char* configuration, int gaussPoint, double determinant) {
  std::ostringstream message;
  message << "det J = " << determinant << " in the " << configuration
          << " configuration at Gauss point " << gaussPoint;
  return {ElementStatus::Code::InvertedJacobian, message.str()};
}

ElementStatus materialFailure(int gaussPoint, const Vector6d& strain) {
  std::ostringstream message;
  message << "material rejected the Green-Lagrange strain [" << strain.transpose()
          << "] at Gauss point " << gaussPoint;
  return {ElementStatus::Code::MaterialFailure, message.str()};
}

ElementStatus notFinite(const char* what) {
  return {ElementStatus::Code::NotFinite, std::string("NaN or Inf in ") + what};
}

}  // namespace cc::tl
