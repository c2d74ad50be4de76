// Every kind of deck error: the exact message and the file:line:column it points at.
#include <gtest/gtest.h>

#include "deck_test_utils.hpp"

namespace cc::test {
namespace {

struct ErrorCase {
  const char* name;
  std::string deck;
  int line;
  int column;
  std::string message;
};

// kMinimalDeck has 7 lines; an appended line is line 8.
std::string appended(const std::string& line) {
  return kMinimalDeck + line + "\n";
}

// The minimal deck with its line `number` (1-based) replaced.
std::string replaced(int number, const std::string& line) {
  std::string deck;
  std::size_t start = 0;
  for (int current = 1; start < kMinimalDeck.size(); ++current) {
    const std::size_t end = kMinimalDeck.find('\n', start);
    deck += (current == number ? line : kMinimalDeck.substr(start, end - start)) + "\n";
    start = end + 1;
  }
  return deck;
}

std::vector<ErrorCase> lexicalAndKeywordCases() {
  return {
      {"UnknownKeywordWithSuggestion", appended("materal soft svk E=1 nu=0.3"), 8, 1,
       "unknown keyword 'materal'; did you mean 'material'?"},
      {"UnknownKeywordWithoutSuggestion", appended("frobnicate 3"), 8, 1,
       "unknown keyword 'frobnicate'; 'covcontact check --keywords' lists them all"},
      {"AbbreviationTooShort", appended("mat soft svk E=1 nu=0.3"), 8, 1,
       "unknown keyword 'mat'; did you mean 'material'?"},
      {"LineStartsWithString", appended("\"title\" x"), 8, 1,
       "expected a keyword at the start of the line, got string \"title\""},
      {"UnterminatedString", appended("title \"no end"), 8, 7,
       "unterminated string: missing closing '\"' on this line"},
      {"ControlCharacter", appended("title \"x\" \x01"), 8, 11,
       "unexpected control character (code 1)"},
      {"ContinuationAtEndOfFile", kMinimalDeck + "title \"x\" \\", 8, 11,
       "line continuation at the end of the file: nothing follows it"},
      {"StrayEquals", appended("reference \"a:b\" =3 value=1"), 8, 17,
       "reference: '=' must follow a parameter name (write NAME=VALUE)"},
  };
}

std::vector<ErrorCase> parameterCases() {
  return {
      {"UnknownParameterWithSuggestion", replaced(3, "elements cube hex8 materail=steel"), 3, 20,
       "elements 'cube': unknown parameter 'materail'; did you mean 'material'?"},
      {"UnknownParameterListsValidOnes", appended("material soft svk E=1 nu=0.3 rho=7.8"), 8, 30,
       "material 'soft': unknown parameter 'rho'; expected one of E or nu"},
      {"KeywordWithoutParameters", appended("fix top ux scale=2"), 8, 12,
       "fix 'top': unknown parameter 'scale': 'fix' takes no NAME=VALUE parameters"},
      {"AmbiguousParameter", replaced(6, "  steps 1 dt=1 grow=2"), 6, 16,
       "steps: ambiguous parameter 'grow': could be grow_after or grow_factor"},
      {"MissingValueBeforeNextParameter", appended("material soft svk E= nu=0.3"), 8, 22,
       "material 'soft': E= has no value; expected a number > 0"},
      {"MissingValueAtEndOfLine", appended("material soft svk nu=0.3 E="), 8, 28,
       "material 'soft': E= has no value; expected a number > 0"},
      {"ParameterWithoutEquals", appended("material soft svk E 2 nu=0.3"), 8, 19,
       "material 'soft': parameter 'E' needs a value: write E=VALUE"},
      {"ParameterGivenTwice", appended("material soft svk E=1 nu=0.3 e=2"), 8, 30,
       "material 'soft': parameter 'E' given twice (first at " + virtualDeckPath() + ":8:21)"},
      {"MissingRequiredParameter", appended("material soft svk nu=0.3"), 8, 1,
       "material 'soft': missing required parameter E= (Young's modulus, a number > 0)"},
      {"MissingPositional", appended("material soft"), 8, 14,
       "material 'soft': missing MODEL (one of svk, neohooke or neohooke_decoupled: St. "
       "Venant-Kirchhoff, compressible neo-Hooke, or decoupled neo-Hooke (Abaqus/CalculiX "
       "form))"},
      {"MissingSetBeforeClause", appended("fix ux"), 8, 5,
       "fix: missing SET before 'ux' (gmsh physical group (its nodes), or `all`: every node of the "
       "mesh)"},
      {"UnexpectedWord", appended("fix top ux sideways"), 8, 12,
       "fix 'top': unexpected word 'sideways'; expected ux, uy, uz or all"},
      {"ClauseGivenTwice", appended("fix top ux ux"), 8, 12,
       "fix 'top': 'ux' given twice (first at " + virtualDeckPath() + ":8:9)"},
  };
}

std::vector<ErrorCase> valueCases() {
  return {
      {"NotANumber", appended("material soft svk E=soft nu=0.3"), 8, 21,
       "material 'soft': E: 'soft' is not a number"},
      {"TrailingGarbage", appended("material soft svk E=2.1e4x nu=0.3"), 8, 21,
       "material 'soft': E: '2.1e4x' is not a valid number (unexpected 'x' after '2.1e4')"},
      {"StringWhereNumberExpected", appended("material soft svk E=\"1\" nu=0.3"), 8, 21,
       "material 'soft': E: expected a number > 0, got string \"1\""},
      {"InfiniteNumber", appended("material soft svk E=inf nu=0.3"), 8, 21,
       "material 'soft': E: 'inf' is not a finite number"},
      {"NotAnInteger", replaced(6, "  steps 2.5 dt=1"), 6, 9, "steps: N: '2.5' is not an integer"},
      {"NegativeYoungsModulus", appended("material soft svk E=-2.1e4 nu=0.3"), 8, 21,
       "material 'soft': E must be > 0, got -2.1e4"},
      {"PoissonRatioHalf", appended("material soft svk E=1 nu=0.5"), 8, 26,
       "material 'soft': nu must be > -1 and < 0.5, got 0.5"},
      {"PoissonRatioMinusOne", appended("material soft svk E=1 nu=-1"), 8, 26,
       "material 'soft': nu must be > -1 and < 0.5, got -1"},
      {"UnknownChoiceWithSuggestion", replaced(3, "elements cube hex9 material=steel"), 3, 15,
       "elements 'cube': TYPE must be one of hex8, solid_shell8 or solid_shell18, got 'hex9'; "
       "did you mean 'hex8'?"},
      {"UnknownListItem", appended("output fields=displacment,stress"), 8, 15,
       "output: fields must be one of displacement, reaction, stress or contact, got "
       "'displacment'; did you mean 'displacement'?"},
      {"ListItemTwice", appended("output fields=stress,stress"), 8, 22,
       "output: fields: 'stress' listed twice"},
      {"BadBool", appended("output csv=maybe"), 8, 12,
       "output: csv must be yes or no, got 'maybe'"},
      {"ShortVector", appended("rigid tool plane normal=(0,1)"), 8, 29,
       "rigid 'tool': normal: expected a vector (x,y,z), got ')'"},
      {"VectorWithWord", appended("rigid tool plane normal=(0,up,1)"), 8, 28,
       "rigid 'tool': normal: 'up' is not a number"},
      {"ZeroSteps", replaced(6, "  steps 0 dt=1"), 6, 9, "steps: N must be >= 1, got 0"},
      {"ZeroDt", replaced(6, "  steps 1 dt=0"), 6, 14, "steps: dt must be > 0, got 0"},
      {"NegativeDt", replaced(6, "  steps 1 dt=-0.1"), 6, 14, "steps: dt must be > 0, got -0.1"},
      {"CutbackFactorOne", replaced(6, "  cutback factor=1"), 6, 18,
       "cutback: factor must be > 0 and < 1, got 1"},
      {"ZeroIterations", replaced(6, "  newton maxit=0"), 6, 16,
       "newton: maxit must be >= 1, got 0"},
      {"StabilizeShareOfOne", replaced(6, "  newton stabilize_share=1"), 6, 26,
       "newton: stabilize_share must be >= 0 and < 1, got 1"},
      {"StabilizeTwoWays", replaced(6, "  steps 1 dt=1 stabilize=0.1 stabilize_share=0.01"), 6, 3,
       "steps: give one of stabilize=C (the factor), stabilize_share=F (the factor chosen by the "
       "run), stabilize_on_failure=C (the factor for failing steps only) and "
       "stabilize_on_failure_share=F (the factor for failing steps, chosen by the run)"},
      {"StabilizeOnFailureAndFactor",
       replaced(6, "  newton stabilize_on_failure=0.1 stabilize=0.1"), 6, 3,
       "newton: give one of stabilize=C (the factor), stabilize_share=F (the factor chosen by "
       "the run), stabilize_on_failure=C (the factor for failing steps only) and "
       "stabilize_on_failure_share=F (the factor for failing steps, chosen by the run)"},
      {"StabilizeOnFailureTwoWays",
       replaced(6, "  newton stabilize_on_failure=0.1 stabilize_on_failure_share=0.01"), 6, 3,
       "newton: give one of stabilize=C (the factor), stabilize_share=F (the factor chosen by "
       "the run), stabilize_on_failure=C (the factor for failing steps only) and "
       "stabilize_on_failure_share=F (the factor for failing steps, chosen by the run)"},
      {"StabilizeOnFailureShareOfOne", replaced(6, "  newton stabilize_on_failure_share=1"), 6, 37,
       "newton: stabilize_on_failure_share must be >= 0 and < 1, got 1"},
      {"NegativeStabilizeOnFailure", replaced(6, "  newton stabilize_on_failure=-1"), 6, 31,
       "newton: stabilize_on_failure must be >= 0, got -1"},
  };
}

std::vector<ErrorCase> functionCases() {
  return {
      {"UnquotedExpression", appended("prescribe top uz -0.1*t"), 8, 18,
       "prescribe 'top': uz: expected a quoted expression such as \"0.1*t\", a number or "
       "'table (t,v) (t,v) ...', got '-0.1*t'"},
      {"EmptyExpression", appended("prescribe top uz \"  \""), 8, 18,
       "prescribe 'top': uz: empty expression"},
      {"MissingFunction", appended("prescribe top uz"), 8, 17,
       "prescribe 'top': 'uz' must be followed by a quoted expression such as \"0.1*t\", a "
       "number or 'table (t,v) (t,v) ...'"},
      {"NoComponents", appended("prescribe top"), 8, 14,
       "prescribe 'top': give at least one component: ux, uy or uz followed by a function"},
      {"TableTimeRepeated", appended("prescribe top uz table (0,0) (1,1) (1,2)"), 8, 36,
       "prescribe 'top': uz table: t must increase strictly from point to point, but t=1 "
       "follows t=1"},
      {"TableTimeDecreasing", appended("load top fz table (0,0) (2,1) (1,2)"), 8, 31,
       "load 'top': fz table: t must increase strictly from point to point, but t=1 follows t=2"},
      {"TableWithoutPoints", appended("load top fz table"), 8, 18,
       "load 'top': fz table: expected a point (t,v), got the end of the line"},
      {"TableMalformedPoint", appended("load top fz table (0 1)"), 8, 22,
       "load 'top': fz table: expected a point (t,v), got '1'"},
      {"FixWithoutComponents", appended("fix top"), 8, 8,
       "fix 'top': give the fixed components: ux, uy, uz or all"},
  };
}

std::vector<ErrorCase> modelCases() {
  const std::string first = virtualDeckPath() + ":2:1";
  return {
      {"UndefinedMaterial", replaced(3, "elements cube hex8 material=stel"), 3, 29,
       "elements 'cube': undefined material 'stel'; did you mean 'steel'?"},
      {"UndefinedMaterialListsDefined", replaced(3, "elements cube hex8 material=rubber"), 3, 29,
       "elements 'cube': undefined material 'rubber' (the deck defines: steel)"},
      {"MaterialNamesAreCaseSensitive", replaced(3, "elements cube hex8 material=Steel"), 3, 29,
       "elements 'cube': undefined material 'Steel'; did you mean 'steel'?"},
      {"DuplicateMaterial", appended("material steel neohooke E=1 nu=0.3"), 8, 10,
       "material 'steel': duplicate material 'steel' (first defined at " + first + ")"},
      {"DuplicateElementGroup", appended("elements cube hex8 material=steel"), 8, 10,
       "elements 'cube': group 'cube' already has elements (at " + virtualDeckPath() + ":3:1)"},
      {"ShellOptionOnHex8", replaced(3, "elements cube hex8 material=steel eas=2"), 3, 39,
       "elements 'cube': eas= applies only to solid_shell8 and solid_shell18 elements"},
      {"MissingMeshFile", replaced(1, "mesh \"meshes/nope.geo\""), 1, 6,
       "mesh: mesh file 'meshes/nope.geo' not found (looked for '" +
           virtualDeckPath("meshes/nope.geo") + "')"},
      {"UnknownMeshExtension", replaced(1, "mesh \"meshes/cube.stl\""), 1, 6,
       "mesh: mesh file 'meshes/cube.stl' has an unknown extension '.stl'; expected a gmsh "
       ".msh or .geo file"},
      {"MeshTwice", appended("mesh \"meshes/cube.geo\""), 8, 1,
       "mesh: 'mesh' given twice (first at " + virtualDeckPath() + ":1:1)"},
      {"MissingMesh", replaced(1, "title \"no mesh\""), 0, 0,
       "no mesh: add a line such as 'mesh \"block.geo\"'"},
      {"MissingElements", replaced(3, "# no elements"), 0, 0,
       "no elements: add a line such as 'elements GROUP hex8 material=NAME'"},
      {"RigidMissingRadius", appended("rigid ball sphere origin=(0,0,2)"), 8, 33,
       "rigid 'ball': a sphere surface needs radius= (cylinder and sphere radius)"},
      {"RigidParameterNotForShape", appended("rigid floor plane normal=(0,0,1) radius=2"), 8, 41,
       "rigid 'floor': radius= does not apply to a plane surface"},
      {"RigidZeroNormal", appended("rigid floor plane normal=(0,0,0)"), 8, 26,
       "rigid 'floor': normal must not be the zero vector"},
      {"ParabolaAxisParallelToNormal",
       appended("rigid p parabolic_cylinder normal=(0,0,1) axis=(0,0,-2) c=1"), 8, 48,
       "rigid 'p': axis must not be parallel to normal"},
      {"DuplicateRigid", appended("rigid a sphere radius=1\nrigid a plane normal=(0,0,1)"), 9, 7,
       "rigid 'a': duplicate rigid surface 'a' (first defined at " + virtualDeckPath() + ":8:1)"},
  };
}

std::vector<ErrorCase> contactCases() {
  const std::string pair = "contact sts master=top slave=bottom eps_n=1";
  return {
      {"MasterEqualsSlave", appended("contact sts master=top slave=top eps_n=1"), 8, 30,
       "contact 'pair1': master and slave are both 'top'; a pair needs two different surfaces"},
      {"NegativeFriction", appended(pair + " eps_t=1 mu=-0.1"), 8, 56,
       "contact: mu must be >= 0, got -0.1"},
      {"ZeroNormalPenalty", appended("contact sts master=top slave=bottom eps_n=0"), 8, 43,
       "contact: eps_n must be > 0, got 0"},
      {"NegativeTangentialPenalty", appended(pair + " eps_t=-5 mu=0.2"), 8, 51,
       "contact: eps_t must be > 0, got -5"},
      {"EpsScaleWithoutAutomaticPenalty", appended(pair + " eps_t=1 mu=0.3 eps_scale=2"), 8, 70,
       "contact 'pair1': eps_scale= scales the automatic penalty, but eps_n= and eps_t= are "
       "both given"},
      {"AugmentationOptionWithPenalty", appended(pair + " aug_tol=1e-4"), 8, 53,
       "contact 'pair1': aug_tol= applies to enforcement=augmented only"},
      {"AccelerationDepthWithPenalty", appended(pair + " aug_depth=3"), 8, 55,
       "contact 'pair1': aug_depth= applies to enforcement=augmented only"},
      {"NegativeAccelerationDepth", appended(pair + " enforcement=augmented aug_depth=-1"), 8, 77,
       "contact: aug_depth must be >= 0 and <= 50, got -1"},
      {"PenaltyGrowthWithPenalty", appended(pair + " aug_grow=no"), 8, 54,
       "contact 'pair1': aug_grow= applies to enforcement=augmented only"},
      {"PenaltyGrowthNotYesOrNo", appended(pair + " enforcement=augmented aug_grow=maybe"), 8, 76,
       "contact: aug_grow must be yes or no, got 'maybe'"},
      {"TangentAndParts", appended(pair + " tangent=main parts=normal_main"), 8, 64,
       "contact 'pair1': give either tangent= or parts=, not both"},
      {"PointsOnNts", appended("contact nts master=top slave=bottom eps_n=1 points=3"), 8, 52,
       "contact 'pair1': points= applies to sts and stas pairs only (nts uses the slave nodes)"},
      {"DuplicatePairName", appended(pair + " name=p\n" + pair + " name=p"), 9, 50,
       "contact 'p': duplicate contact pair name 'p' (first at " + virtualDeckPath() + ":8:1)"},
      {"DefaultNameClash", appended(pair + " name=pair2\n" + pair), 9, 1,
       "contact 'pair2': duplicate contact pair name 'pair2' (first at " + virtualDeckPath() +
           ":8:1)"},
      {"StasSlaveNotRigid", appended("contact stas master=top slave=bottom eps_n=1"), 8, 31,
       "contact 'pair1': an stas pair needs a 'rigid' surface as its slave, but 'bottom' is not "
       "one (the deck defines no rigid surface)"},
      {"StasSlaveTypo",
       appended("rigid tool plane normal=(0,0,1)\ncontact stas master=top slave=tol eps_n=1"), 9,
       31,
       "contact 'pair1': an stas pair needs a 'rigid' surface as its slave, but 'tol' is not one; "
       "did you mean 'tool'?"},
      {"StsSlaveRigid",
       appended("rigid tool plane normal=(0,0,1)\ncontact sts master=top slave=tool eps_n=1"), 9,
       30,
       "contact 'pair1': slave 'tool' is a rigid surface, but an sts pair needs a face set of "
       "the mesh here (a rigid surface can only be the slave of an stas pair)"},
      {"StasMasterRigid",
       appended("rigid tool plane normal=(0,0,1)\nrigid ball sphere radius=1\n"
                "contact stas master=tool slave=ball eps_n=1"),
       10, 21,
       "contact 'pair1': master 'tool' is a rigid surface, but an stas pair needs a face set of "
       "the mesh here (a rigid surface can only be the slave of an stas pair)"},
      {"ReferenceWithoutValue", appended("reference reaction:top:z"), 8, 25,
       "reference: give one of value=NUMBER, table (t,v) ... or analytic NAME"},
      {"ReferenceExtraWithoutAnalytic", appended("reference reaction:top:z valu=1 R=2"), 8, 33,
       "reference: unknown parameter 'R'; NAME=NUMBER parameters are allowed only with "
       "'analytic NAME'"},
  };
}

std::vector<ErrorCase> solveCases() {
  const std::string model =
      "mesh \"meshes/cube.geo\"\nmaterial steel svk E=200 nu=0.3\n"
      "elements cube hex8 material=steel\n";  // 3 lines
  const std::string solveAt = virtualDeckPath() + ":4:1";
  return {
      {"MissingSolve", model, 0, 0, "no solve block: add 'solve', a line 'steps N dt=D' and 'end'"},
      {"EndWithoutSolve", model + "end\n", 4, 1, "'end' without a matching 'solve'"},
      {"UnclosedSolve", model + "solve\nsteps 1 dt=1\n", 4, 1,
       "the solve block is never closed; add 'end' after its last command"},
      {"EmptySolve", model + "solve\nnewton maxit=3\nend\n", 4, 1,
       "end: the solve block has no 'steps' line; add e.g. 'steps 10 dt=0.1' before 'end'"},
      {"ModelKeywordInSolve", model + "solve\nsteps 1 dt=1\nfix top all\nend\n", 6, 1,
       "'fix' describes the model and cannot appear inside the solve block (opened at " + solveAt +
           "); close the block with 'end' first"},
      {"StepsOutsideSolve", model + "steps 1 dt=1\n", 4, 1,
       "'steps' belongs inside the solve block: write it between 'solve' and 'end'"},
      {"SecondSolve", model + "solve\nsteps 1 dt=1\nend\nsolve\nsteps 1 dt=1\nend\n", 7, 1,
       "solve: a deck has one solve block; the first one starts at " + solveAt},
      {"MissingDt", model + "solve\nsteps 1\nend\n", 5, 1,
       "steps: missing required parameter dt= (time step size, a number > 0)"},
  };
}

void checkCases(const std::vector<ErrorCase>& cases) {
  for (const ErrorCase& c : cases) {
    SCOPED_TRACE(c.name);
    const InputError error = parseError(c.deck);
    EXPECT_EQ(error.bareMessage(), c.message);
    EXPECT_EQ(error.where().file, virtualDeckPath());
    EXPECT_EQ(error.where().line, c.line);
    EXPECT_EQ(error.where().column, c.column);
  }
}

TEST(DeckErrors, LexicalAndKeyword) {
  checkCases(lexicalAndKeywordCases());
}
TEST(DeckErrors, Parameters) {
  checkCases(parameterCases());
}
TEST(DeckErrors, Values) {
  checkCases(valueCases());
}
TEST(DeckErrors, Functions) {
  checkCases(functionCases());
}
TEST(DeckErrors, Model) {
  checkCases(modelCases());
}
TEST(DeckErrors, Contact) {
  checkCases(contactCases());
}
TEST(DeckErrors, SolveBlock) {
  checkCases(solveCases());
}

TEST(DeckErrors, WhatStartsWithFileLineColumn) {
  const InputError error = parseError(appended("materal soft svk E=1 nu=0.3"));
  EXPECT_EQ(std::string(error.what()), virtualDeckPath() +
                                           ":8:1: error: unknown keyword 'materal'; did you mean "
                                           "'material'?");
}

}  // namespace
}  // namespace cc::test
