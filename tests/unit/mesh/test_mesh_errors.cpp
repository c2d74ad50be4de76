// Bad meshes and bad mesh commands: every case must raise an InputError at the deck location
// of the mesh command, with a message that says what is wrong.
#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "mesh/geo_parameters.hpp"
#include "mesh/gmsh_import.hpp"
#include "mesh_test_utils.hpp"

namespace cc {
namespace {

const SourceLocation kDeckLine{"decks/example.deck", 7, 3};

MeshSpec specFor(const std::filesystem::path& path,
                 const std::map<std::string, double>& parameters = {}) {
  MeshSpec spec;
  spec.path = path.string();
  spec.parameters = parameters;
  spec.where = kDeckLine;
  return spec;
}

// Loads and expects an InputError at kDeckLine whose message contains every fragment.
void expectInputError(const MeshSpec& spec, const std::vector<std::string>& fragments) {
  try {
    loadMesh(spec);
    ADD_FAILURE() << "no error for " << spec.path;
  } catch (const InputError& error) {
    EXPECT_EQ(error.where().file, kDeckLine.file);
    EXPECT_EQ(error.where().line, kDeckLine.line);
    EXPECT_EQ(error.where().column, kDeckLine.column);
    for (const std::string& fragment : fragments) {
      EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos)
          << "missing '" << fragment << "' in: " << error.what();
    }
  }
}

// A unit cube of n^3 hexahedra extruded from the square [0,1]^2; `extra` is appended.
std::string extrudedCube(const std::string& extra, const std::string& volumeGroup =
                                                       "Physical Volume(\"solid\") = {v[1]};\n") {
  return "Point(1) = {0,0,0}; Point(2) = {1,0,0}; Point(3) = {1,1,0}; Point(4) = {0,1,0};\n"
         "Line(1) = {1,2}; Line(2) = {2,3}; Line(3) = {3,4}; Line(4) = {4,1};\n"
         "Curve Loop(1) = {1,2,3,4}; Plane Surface(1) = {1};\n"
         "Transfinite Curve{1:4} = 3; Transfinite Surface{1}; Recombine Surface{1};\n"
         "v[] = Extrude{0,0,1}{ Surface{1}; Layers{2}; Recombine; };\n" +
         volumeGroup + extra;
}

TEST(MeshErrors, MissingFile) {
  expectInputError(specFor("/nonexistent/dir/block.geo"),
                   {"mesh file '/nonexistent/dir/block.geo' does not exist"});
}

TEST(MeshErrors, UnsupportedExtension) {
  const auto dir = test::scratchDir("extension");
  test::writeText(dir / "mesh.vtk", "# vtk DataFile Version 2.0\n");
  expectInputError(specFor(dir / "mesh.vtk"), {"must be a gmsh .msh or .geo file"});
}

TEST(MeshErrors, GeoSyntaxErrorCarriesGmshMessage) {
  const auto dir = test::scratchDir("syntax");
  test::writeText(dir / "broken.geo", "Point(1) = {0, 0, 0};\nPoint(2) = {1, 0;\n");
  expectInputError(specFor(dir / "broken.geo"),
                   {"gmsh could not mesh", "broken.geo", "line 2", "syntax error"});
}

TEST(MeshErrors, ErrorRaisedByTheGeoFile) {
  expectInputError(specFor(test::meshesDir() + "/cube.geo", {{"n", 1}}),
                   {"cube.geo: n must be at least 2"});
}

TEST(MeshErrors, UnknownParameterListsTheDeclaredOnes) {
  expectInputError(
      specFor(test::meshesDir() + "/cube.geo", {{"nn", 3}}),
      {"mesh parameter 'nn' is not declared with DefineConstant", "(it declares: distort, n)"});
}

TEST(MeshErrors, ParametersOnAMshFile) {
  const auto dir = test::scratchDir("msh_parameters");
  test::writeText(dir / "any.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n");
  expectInputError(specFor(dir / "any.msh", {{"n", 2}}), {"apply only to .geo files"});
}

TEST(MeshErrors, TetrahedraAreRejected) {
  const auto dir = test::scratchDir("tetrahedra");
  test::writeText(dir / "tets.geo",
                  "SetFactory(\"OpenCASCADE\");\nBox(1) = {0,0,0, 1,1,1};\n"
                  "Mesh.MeshSizeMax = 0.5;\nPhysical Volume(\"solid\") = {1};\n");
  expectInputError(specFor(dir / "tets.geo"),
                   {"physical volume 'solid'", "gmsh element type 4",
                    "tetrahedra are not supported; mesh with Recombine/transfinite hexahedra"});
}

TEST(MeshErrors, SerendipityHexahedraAreRejected) {
  const auto dir = test::scratchDir("hex20");
  test::writeText(dir / "hex20.geo",
                  extrudedCube("Mesh.ElementOrder = 2;\nMesh.SecondOrderIncomplete = 1;\n"));
  expectInputError(specFor(dir / "hex20.geo"),
                   {"20-node hexahedra are not supported", "Mesh.SecondOrderIncomplete = 0"});
}

TEST(MeshErrors, InvertedElementNamesTagGroupAndValue) {
  // One unit-cube hexahedron (gmsh element 41) whose top and bottom faces are swapped:
  // the map from [-1,1]^3 has det J = -(1/2)^3 everywhere.
  const auto dir = test::scratchDir("inverted");
  test::writeText(dir / "inverted.msh",
                  "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
                  "$PhysicalNames\n1\n3 1 \"solid\"\n$EndPhysicalNames\n"
                  "$Nodes\n8\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n"
                  "5 0 0 1\n6 1 0 1\n7 1 1 1\n8 0 1 1\n$EndNodes\n"
                  "$Elements\n1\n41 5 2 1 1 5 6 7 8 1 2 3 4\n$EndElements\n");
  expectInputError(
      specFor(dir / "inverted.msh"),
      {"inverted element: gmsh element 41 of group 'solid'", "Jacobian determinant -0.125"});
}

TEST(MeshErrors, FaceGroupOffTheBoundary) {
  const auto dir = test::scratchDir("floating");
  test::writeText(dir / "floating.geo",
                  extrudedCube("Point(101) = {0,0,3}; Point(102) = {1,0,3}; Point(103) = {1,1,3};\n"
                               "Point(104) = {0,1,3};\nLine(101) = {101,102};\n"
                               "Line(102) = {102,103}; Line(103) = {103,104};\n"
                               "Line(104) = {104,101}; Curve Loop(101) = {101:104};\n"
                               "Plane Surface(101) = {101}; Transfinite Curve{101:104} = 2;\n"
                               "Transfinite Surface{101}; Recombine Surface{101};\n"
                               "Physical Surface(\"floating\") = {101};\n"));
  expectInputError(specFor(dir / "floating.geo"),
                   {"face set 'floating'", "is not a face of any volume element"});
}

TEST(MeshErrors, InteriorFaceGroupIsRejected) {
  // cube.geo's surfaces 5..8 are the interior plane z = 1/2 between its sub-blocks.
  const auto dir = test::scratchDir("interior");
  test::writeText(
      dir / "interior.geo",
      "Include \"" + test::meshesDir() + "/cube.geo\";\nPhysical Surface(\"middle\") = {5:8};\n");
  expectInputError(specFor(dir / "interior.geo", {{"n", 2}}),
                   {"face set 'middle'", "interior face shared by 2 volume elements"});
}

TEST(MeshErrors, UnnamedGroup) {
  const auto dir = test::scratchDir("unnamed");
  test::writeText(dir / "unnamed.geo", extrudedCube("", "Physical Volume(7) = {v[1]};\n"));
  expectInputError(specFor(dir / "unnamed.geo"), {"the physical volume with tag 7 has no name"});
}

TEST(MeshErrors, DuplicateGroupName) {
  const auto dir = test::scratchDir("duplicate");
  test::writeText(dir / "duplicate.geo", extrudedCube("Physical Surface(\"solid\") = {1};\n"));
  expectInputError(specFor(dir / "duplicate.geo"),
                   {"'solid' is used by a physical surface and a physical volume"});
}

TEST(MeshErrors, NoPhysicalVolume) {
  const auto dir = test::scratchDir("no_volume");
  test::writeText(dir / "surface_only.geo",
                  extrudedCube("Physical Surface(\"bottom\") = {1};\n", ""));
  expectInputError(specFor(dir / "surface_only.geo"), {"the mesh has no physical volume"});
}

TEST(GeoParameters, DefineConstantNamesSkipCommentsAndFollowIncludes) {
  const auto dir = test::scratchDir("geo_parameters");
  test::writeText(dir / "inner.geo", "DefineConstant[ inner = {1, Name \"P/inner\"} ];\n");
  test::writeText(dir / "outer.geo",
                  "// DefineConstant[ commented = 1 ];\n"
                  "/* DefineConstant[ blockComment = 2 ]; */\n"
                  "DefineConstant[ a = 1, b = {2, Min 1, Max 3, Name \"P/b, not c\"},\n"
                  "                list[] = {1, 2}, s = \"text = x\" ];\n"
                  "Printf(\"DefineConstant[ inString = 1 ]\");\n"
                  "Include \"inner.geo\";\n");
  const std::set<std::string> expected{"a", "b", "list", "s", "inner"};
  EXPECT_EQ(geoDefinedConstants((dir / "outer.geo").string()), expected);
  const std::set<std::string> blockOnBase{"nx",         "ny",          "nz",          "nbx",
                                          "nby",        "blockLength", "blockHeight", "thickness",
                                          "baseLength", "baseHeight",  "gap"};
  EXPECT_EQ(geoDefinedConstants(test::meshesDir() + "/block_on_base.geo"), blockOnBase);
}

}  // namespace
}  // namespace cc
