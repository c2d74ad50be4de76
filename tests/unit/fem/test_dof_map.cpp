// DofMap: free equations first in node order, prescribed numbered separately, inactive nodes
// without equations.
#include <gtest/gtest.h>

#include "fem/dof_map.hpp"

namespace cc {
namespace {

TEST(DofMap, NumbersFreeDofsInNodeOrderAndPrescribedSeparately) {
  // Node 1 is inactive (its constraint flag must not matter); node 2 has uy prescribed.
  const std::vector<bool> active{true, false, true};
  const std::vector<bool> constrained{false, false, false, true, false, false, false, true, false};
  const DofMap dofs(active, constrained);
  EXPECT_EQ(dofs.numNodes(), 3);
  EXPECT_EQ(dofs.numFree(), 5);
  EXPECT_EQ(dofs.numPrescribed(), 1);
  EXPECT_EQ(dofs.freeDofs(), (std::vector<int>{0, 1, 2, 6, 8}));
  EXPECT_EQ(dofs.prescribedDofs(), (std::vector<int>{7}));
  for (int dof = 3; dof < 6; ++dof) {
    EXPECT_EQ(dofs.kind(dof), DofMap::Kind::Inactive);
    EXPECT_EQ(dofs.equation(dof), -1);
    EXPECT_EQ(dofs.prescribedIndex(dof), -1);
  }
  EXPECT_EQ(dofs.kind(7), DofMap::Kind::Prescribed);
  EXPECT_EQ(dofs.prescribedIndex(7), 0);
  EXPECT_EQ(dofs.equation(7), -1);
  EXPECT_EQ(dofs.kind(8), DofMap::Kind::Free);
  EXPECT_EQ(dofs.equation(8), 4);
  for (int e = 0; e < dofs.numFree(); ++e) EXPECT_EQ(dofs.equation(dofs.freeDofs()[e]), e);
}

TEST(DofMap, RejectsConstraintFlagsOfWrongLength) {
  EXPECT_THROW(DofMap(std::vector<bool>(2, true), std::vector<bool>(5, false)),
               std::invalid_argument);
}

}  // namespace
}  // namespace cc
