// The sparse matrix type of the whole program (column-major, 32-bit indices), declared once so that
// the assembler and the sparsity pattern builder share it without including each other.
#pragma once

#include <Eigen/SparseCore>

namespace cc {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

}  // namespace cc
