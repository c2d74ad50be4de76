// Deck texts of the unit cube (meshes/cube.geo) that tests in more than one folder run, each
// written once here. The mesh path is absolute, so a text runs in-process under any virtual path
// and from a file in any scratch directory. Header only: COVCONTACT_SOURCE_DIR comes from the
// test target (cc_add_gtest, cc_stress_support).
#pragma once

#include <string>

namespace cc::test {

// The unit cube (2 x 2 x 2 Hex8, neo-Hooke E = 100, nu = 0.3) clamped at its bottom and pulled
// at its top by a total force 10 t. solveLines: the lines of its solve block, each ending in a
// newline (e.g. "  steps 4 dt=0.25 stabilize_share=0.05\n").
inline std::string clampedCubeDeck(const std::string& solveLines) {
  return "mesh \"" + std::string(COVCONTACT_SOURCE_DIR) +
         "/meshes/cube.geo\" n=2\n"
         "material m neohooke E=100 nu=0.3\n"
         "elements cube hex8 material=m\n"
         "fix zmin all\n"
         "load zmax fz \"10*t\" total\n"
         "solve\n" +
         solveLines + "end\n";
}

// The same cube with no support at all, pushed in z by a total force on its top face: a free
// body, whose tangent is singular without viscous stabilisation. newtonLine: empty or a
// `newton` line ending in a newline.
inline std::string freeCubeDeck(const std::string& newtonLine, const std::string& force = "10*t",
                                const std::string& steps = "4 dt=0.25") {
  return "mesh \"" + std::string(COVCONTACT_SOURCE_DIR) +
         "/meshes/cube.geo\" n=2\n"
         "material m neohooke E=100 nu=0.3\n"
         "elements cube hex8 material=m\n"
         "load zmax fz \"" +
         force +
         "\" total\n"
         "solve\n" +
         newtonLine + "  steps " + steps + "\nend\n";
}

}  // namespace cc::test
