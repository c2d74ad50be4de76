// Newton systems as data (`covcontact run --dump-tangent STEP:ITER`, issue 13): the free
// tangent K_ff, the right-hand side, where each equation sits in the mesh and the six
// rigid-body modes, in PETSc's binary format (big-endian; MatLoad/VecLoad read it, and so does
// readTangentDump), so that every solver configuration can be measured on real tangents
// (scripts/solver_survey.py) without running the model again.
//   DIR/matrix.petsc        K_ff (AIJ, rows = free equations)
//   DIR/rhs.petsc           right-hand side of that iteration
//   DIR/nullspace.petsc     6 vectors: translations x, y, z and rotations about x, y, z through
//                           the centroid, restricted to the free equations
//   DIR/free_dofs.petsc     nodal dof (3 node + component) of each equation, as reals
//   DIR/coordinates.petsc   current nodal coordinates, x y z per node
//   DIR/info.txt            equations, nonzeros, symmetric (0/1), nodes
#pragma once

#include <Eigen/Core>
#include <string>

#include "fem/assembler.hpp"
#include "fem/dof_map.hpp"
#include "solver/linear_solver.hpp"

namespace cc {

// Creates DIR if needed; throws std::runtime_error naming the file that could not be written.
void writeTangentDump(const std::string& directory, const SystemMatrices& system,
                      const Eigen::VectorXd& rhs, const DofMap& dofs,
                      const Eigen::Matrix3Xd& coordinates);

struct TangentDump {
  SparseMatrix matrix;
  Eigen::VectorXd rhs;
  Eigen::MatrixXd nullspace;  // equations x 6
  SystemLayout layout;
  bool symmetric = true;
};
TangentDump readTangentDump(const std::string& directory);

}  // namespace cc
