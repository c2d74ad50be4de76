// Isotropic elastic constants: conversion from Young's modulus and Poisson's ratio to the Lame
// constants (validated) and the small-strain Hooke matrix in Voigt notation.
#pragma once

#include "materials/material.hpp"

namespace cc {

struct LameParameters {
  double lambda = 0;  // first Lame constant
  double mu = 0;      // shear modulus
};

// Throws std::invalid_argument unless E > 0 and -1 < nu < 1/2 (the range in which the strain
// energy is positive definite). The deck layer reports the user-facing InputError before this.
LameParameters lameParameters(double youngsModulus, double poissonRatio);

// Hooke's law S = lambda tr(E) I + 2 mu E as a Voigt matrix acting on engineering strains.
Matrix6d hookeMatrix(const LameParameters& lame);

}  // namespace cc
