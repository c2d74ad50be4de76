// Decks that must parse: a deck using every keyword becomes exactly the expected ProblemSpec;
// abbreviations, case, comments, continuation lines, number formats and solve-block semantics.
#include <gtest/gtest.h>

#include <filesystem>

#include "deck/parsed_line.hpp"
#include "deck_test_utils.hpp"

namespace cc::test {
namespace {

namespace fs = std::filesystem;

std::string meshPath(const std::string& name) {
  return (fs::path(COVCONTACT_SOURCE_DIR) / "tests/decks/meshes" / name).lexically_normal();
}

const std::string kCompleteDeck = R"deck(# A deck exercising every keyword
title "Block on base: every keyword"
mesh "meshes/two_blocks.geo" n=3 Scale=0.5
material soft svk E=2.1e4 nu=0.3
material hard neohooke E=2.1e6 nu=-0.25
elements block solid_shell8 material=soft thickness=z eas=2
elements base hex8 material=hard
fix base_bottom all
fix block_top ux uy
prescribe block_top uz "-0.1*min(t,1)" ux table (0,0) (1,0) (2,0.5)
load block_top fy 2.5 total
load base_top fz "x*t"
rigid ball sphere origin=(0.5,0.5,1.5) radius=0.25 uz "-0.2*t"
rigid floor plane origin=(0,0,-0.5) normal=(0,0,1)
rigid roller cylinder axis=(0,1,0) radius=1
rigid trough parabolic_cylinder normal=(0,0,1) axis=(1,0,0) c=0.5
contact sts master=block_bottom slave=base_top eps_n=2.1e6 eps_t=1e5 mu=0.3 points=3 \
        tangent=no_curvature name=interface
contact nts master=base_top slave=block_bottom eps_n=1e6
contact stas master=block_top slave=ball eps_n=1e5 parts=normal_main,stick_main
output file="results/run.h5" fields=displacement,stress csv=no xdmf=yes
reference reaction:block_top:z value=-12.5
reference "contact:interface:force:z" table (0,0) (1,-3)
reference contact:pair3:force:z analytic hertz_sphere R=0.25 E=2.1e4
solve
  newton maxit=12 converge=both
  cutback max=4 factor=0.25
  steps 1 dt=1 energy=1e-20
  newton residual=1e-8
  steps 20 dt=0.05 output_every=5 cutback_max=2 line_search=yes
end
)deck";

// The complete deck is parsed once and checked item by item.
const ProblemSpec& completeSpec() {
  static const ProblemSpec spec = parseDeckText(kCompleteDeck, virtualDeckPath("complete.deck"));
  return spec;
}

// The viscous factor is set one way at a time: a phase's stabilize_share= replaces the newton
// line's stabilize= for that phase only, and a later newton line's stabilize= the share;
// stabilize_on_failure= and stabilize_on_failure_share= likewise.
TEST(DeckParser, StabilizeAndStabilizeShareReplaceEachOther) {
  const ProblemSpec spec = parseDeckText(kMinimalDeck.substr(0, kMinimalDeck.find("solve")) +
                                             "solve\n"
                                             "  newton stabilize=0.01\n"
                                             "  steps 1 dt=1\n"
                                             "  steps 1 dt=1 stabilize_share=0.02\n"
                                             "  steps 1 dt=1\n"
                                             "  newton stabilize_share=0.03\n"
                                             "  steps 1 dt=1\n"
                                             "  steps 1 dt=1 stabilize_on_failure=0.04\n"
                                             "  newton stabilize_on_failure=0.05\n"
                                             "  steps 1 dt=1\n"
                                             "  steps 1 dt=1 stabilize=0.06\n"
                                             "  steps 1 dt=1 stabilize_on_failure_share=0.07\n"
                                             "  newton stabilize_on_failure_share=0.08\n"
                                             "  steps 1 dt=1\n"
                                             "  steps 1 dt=1 stabilize_on_failure=0.09\n"
                                             "end\n",
                                         virtualDeckPath());
  ASSERT_EQ(spec.phases.size(), 10u);
  const double factors[] = {0.01, 0, 0.01, 0, 0, 0, 0.06, 0, 0, 0};
  const double shares[] = {0, 0.02, 0, 0.03, 0, 0, 0, 0, 0, 0};
  const double onFailure[] = {0, 0, 0, 0, 0.04, 0.05, 0, 0, 0, 0.09};
  const double onFailureShares[] = {0, 0, 0, 0, 0, 0, 0, 0.07, 0.08, 0};
  for (std::size_t i = 0; i < 10; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(spec.phases[i].newton.stabilization, factors[i]);
    EXPECT_EQ(spec.phases[i].newton.stabilizationShare, shares[i]);
    EXPECT_EQ(spec.phases[i].newton.stabilizationOnFailure, onFailure[i]);
    EXPECT_EQ(spec.phases[i].newton.stabilizationOnFailureShare, onFailureShares[i]);
  }
}

TEST(CompleteDeck, SourceTitleAndMesh) {
  const ProblemSpec& spec = completeSpec();
  EXPECT_EQ(spec.title, "Block on base: every keyword");
  EXPECT_EQ(spec.deckPath, virtualDeckPath("complete.deck"));
  EXPECT_EQ(spec.deckText, kCompleteDeck);

  EXPECT_EQ(spec.mesh.path, meshPath("two_blocks.geo"));
  EXPECT_EQ(spec.mesh.parameters, (std::map<std::string, double>{{"n", 3}, {"Scale", 0.5}}));
  EXPECT_EQ(spec.mesh.where.line, 3);
}

TEST(CompleteDeck, MaterialsAndElements) {
  const ProblemSpec& spec = completeSpec();
  ASSERT_EQ(spec.materials.size(), 2u);
  EXPECT_EQ(spec.materials[0].name, "soft");
  EXPECT_EQ(spec.materials[0].model, MaterialSpec::Model::StVenantKirchhoff);
  EXPECT_EQ(spec.materials[0].youngsModulus, 2.1e4);
  EXPECT_EQ(spec.materials[0].poissonRatio, 0.3);
  EXPECT_EQ(spec.materials[1].model, MaterialSpec::Model::NeoHooke);
  EXPECT_EQ(spec.materials[1].youngsModulus, 2.1e6);
  EXPECT_EQ(spec.materials[1].poissonRatio, -0.25);
  EXPECT_EQ(spec.materials[1].where.line, 5);
  EXPECT_EQ(spec.materials[1].where.column, 1);

  ASSERT_EQ(spec.elementBlocks.size(), 2u);
  EXPECT_EQ(spec.elementBlocks[0].group, "block");
  EXPECT_EQ(spec.elementBlocks[0].type, ElementBlockSpec::Type::SolidShell8);
  EXPECT_EQ(spec.elementBlocks[0].material, "soft");
  EXPECT_EQ(spec.elementBlocks[0].thicknessAxis, 2);
  EXPECT_EQ(spec.elementBlocks[0].easParameters, 2);
  EXPECT_EQ(spec.elementBlocks[1].type, ElementBlockSpec::Type::Hex8);
  EXPECT_EQ(spec.elementBlocks[1].thicknessAxis, -1);
  EXPECT_EQ(spec.elementBlocks[1].easParameters, 1);
}

TEST(CompleteDeck, BoundaryConditionsAndLoads) {
  const ProblemSpec& spec = completeSpec();
  ASSERT_EQ(spec.fixes.size(), 2u);
  EXPECT_EQ(spec.fixes[0].set, "base_bottom");
  EXPECT_EQ(spec.fixes[0].components, (std::array<bool, 3>{true, true, true}));
  EXPECT_EQ(spec.fixes[1].components, (std::array<bool, 3>{true, true, false}));

  ASSERT_EQ(spec.prescribed.size(), 1u);
  const PrescribeSpec& prescribed = spec.prescribed[0];
  EXPECT_EQ(prescribed.set, "block_top");
  ASSERT_TRUE(prescribed.components[0] && prescribed.components[2]);
  EXPECT_FALSE(prescribed.components[1]);
  EXPECT_EQ(prescribed.components[2]->kind, FunctionSpec::Kind::Expression);
  EXPECT_EQ(prescribed.components[2]->expression, "-0.1*min(t,1)");
  EXPECT_EQ(prescribed.components[2]->where.line, 10);
  EXPECT_EQ(prescribed.components[2]->where.column, 24);  // the opening quote
  EXPECT_EQ(prescribed.components[0]->kind, FunctionSpec::Kind::Table);
  EXPECT_EQ(prescribed.components[0]->table,
            (std::vector<std::pair<double, double>>{{0, 0}, {1, 0}, {2, 0.5}}));

  ASSERT_EQ(spec.loads.size(), 2u);
  EXPECT_TRUE(spec.loads[0].total);
  ASSERT_TRUE(spec.loads[0].components[1]);
  EXPECT_EQ(spec.loads[0].components[1]->expression, "2.5");
  EXPECT_FALSE(spec.loads[0].components[0] || spec.loads[0].components[2]);
  EXPECT_FALSE(spec.loads[1].total);
  EXPECT_EQ(spec.loads[1].components[2]->expression, "x*t");
}

TEST(CompleteDeck, RigidSurfaces) {
  const ProblemSpec& spec = completeSpec();
  ASSERT_EQ(spec.rigidSurfaces.size(), 4u);
  const RigidSurfaceSpec& ball = spec.rigidSurfaces[0];
  EXPECT_EQ(ball.name, "ball");
  EXPECT_EQ(ball.shape, RigidSurfaceSpec::Shape::Sphere);
  EXPECT_EQ(ball.origin, (Vec3{0.5, 0.5, 1.5}));
  EXPECT_EQ(ball.radius, 0.25);
  ASSERT_TRUE(ball.motion[2]);
  EXPECT_EQ(ball.motion[2]->expression, "-0.2*t");
  EXPECT_FALSE(ball.motion[0] || ball.motion[1]);
  EXPECT_EQ(spec.rigidSurfaces[1].shape, RigidSurfaceSpec::Shape::Plane);
  EXPECT_EQ(spec.rigidSurfaces[1].normal, (Vec3{0, 0, 1}));
  EXPECT_EQ(spec.rigidSurfaces[1].origin, (Vec3{0, 0, -0.5}));
  EXPECT_EQ(spec.rigidSurfaces[2].shape, RigidSurfaceSpec::Shape::Cylinder);
  EXPECT_EQ(spec.rigidSurfaces[2].origin, (Vec3{0, 0, 0}));
  EXPECT_EQ(spec.rigidSurfaces[2].axis, (Vec3{0, 1, 0}));
  EXPECT_EQ(spec.rigidSurfaces[2].radius, 1.0);
  EXPECT_EQ(spec.rigidSurfaces[3].shape, RigidSurfaceSpec::Shape::ParabolicCylinder);
  EXPECT_EQ(spec.rigidSurfaces[3].axis, (Vec3{1, 0, 0}));
  EXPECT_EQ(spec.rigidSurfaces[3].curvature, 0.5);
}

TEST(CompleteDeck, ContactPairs) {
  const ProblemSpec& spec = completeSpec();
  ASSERT_EQ(spec.contacts.size(), 3u);
  const ContactSpec& sts = spec.contacts[0];
  EXPECT_EQ(sts.name, "interface");
  EXPECT_EQ(sts.kind, ContactSpec::Kind::SegmentToSegment);
  EXPECT_EQ(sts.master, "block_bottom");
  EXPECT_EQ(sts.slave, "base_top");
  EXPECT_EQ(sts.penaltyNormal, 2.1e6);
  EXPECT_EQ(sts.penaltyTangential, 1e5);
  EXPECT_EQ(sts.friction, 0.3);
  EXPECT_EQ(sts.integrationPoints, 3);
  EXPECT_EQ(sts.tangentMode, ContactSpec::TangentMode::Paper);
  EXPECT_TRUE(sts.parts.normalMain && sts.parts.normalRotational && sts.parts.stickMain &&
              sts.parts.stickRotational && sts.parts.slideConstitutive &&
              sts.parts.slideRotational);
  EXPECT_FALSE(sts.parts.normalCurvature || sts.parts.stickCurvature || sts.parts.slideCurvature ||
               sts.parts.slideUnsymmetricCurvature);
  const ContactSpec& nts = spec.contacts[1];
  EXPECT_EQ(nts.name, "pair2");
  EXPECT_EQ(nts.kind, ContactSpec::Kind::NodeToSegment);
  EXPECT_EQ(nts.friction, 0.0);
  EXPECT_EQ(nts.penaltyTangential, 0.0);
  EXPECT_EQ(nts.integrationPoints, 2);
  const ContactSpec& stas = spec.contacts[2];
  EXPECT_EQ(stas.name, "pair3");
  EXPECT_EQ(stas.kind, ContactSpec::Kind::SegmentToAnalytical);
  EXPECT_EQ(stas.slave, "ball");
  EXPECT_TRUE(stas.parts.normalMain && stas.parts.stickMain);
  EXPECT_FALSE(stas.parts.normalRotational || stas.parts.normalCurvature ||
               stas.parts.stickRotational || stas.parts.stickCurvature ||
               stas.parts.slideConstitutive || stas.parts.slideRotational ||
               stas.parts.slideCurvature || stas.parts.slideUnsymmetricCurvature);
}

TEST(CompleteDeck, OutputAndReferences) {
  const ProblemSpec& spec = completeSpec();
  EXPECT_EQ(spec.output.file, "results/run.h5");
  EXPECT_TRUE(spec.output.displacement && spec.output.stress);
  EXPECT_FALSE(spec.output.reaction || spec.output.contact);
  EXPECT_FALSE(spec.output.csv);
  EXPECT_TRUE(spec.output.xdmf);

  ASSERT_EQ(spec.references.size(), 3u);
  EXPECT_EQ(spec.references[0].quantity, "reaction:block_top:z");
  EXPECT_EQ(spec.references[0].value, -12.5);
  EXPECT_EQ(spec.references[1].quantity, "contact:interface:force:z");
  EXPECT_FALSE(spec.references[1].value);
  EXPECT_EQ(spec.references[1].table, (std::vector<std::pair<double, double>>{{0, 0}, {1, -3}}));
  EXPECT_EQ(spec.references[2].analytic, "hertz_sphere");
  EXPECT_EQ(spec.references[2].parameters,
            (std::map<std::string, double>{{"R", 0.25}, {"E", 2.1e4}}));
}

TEST(CompleteDeck, PhasesWithStickyAndPhaseOnlySettings) {
  const ProblemSpec& spec = completeSpec();
  ASSERT_EQ(spec.phases.size(), 2u);
  const PhaseSpec& press = spec.phases[0];
  EXPECT_EQ(press.steps, 1);
  EXPECT_EQ(press.dt, 1.0);
  EXPECT_EQ(press.outputEvery, 1);
  EXPECT_EQ(press.newton.maxIterations, 12);
  EXPECT_EQ(press.newton.criterion, NewtonSpec::Criterion::Both);
  EXPECT_EQ(press.newton.energyTolerance, 1e-20);
  EXPECT_EQ(press.newton.residualTolerance, 1e-10);
  EXPECT_FALSE(press.newton.lineSearch);
  EXPECT_EQ(press.cutback.maxCutbacks, 4);
  EXPECT_EQ(press.cutback.factor, 0.25);
  EXPECT_EQ(press.where.line, 28);
  const PhaseSpec& slide = spec.phases[1];
  EXPECT_EQ(slide.steps, 20);
  EXPECT_EQ(slide.dt, 0.05);
  EXPECT_EQ(slide.outputEvery, 5);
  EXPECT_EQ(slide.newton.maxIterations, 12);        // sticky from `newton`
  EXPECT_EQ(slide.newton.residualTolerance, 1e-8);  // sticky, set between the phases
  EXPECT_EQ(slide.newton.energyTolerance, 1e-16);   // phase 1's override did not stick
  EXPECT_TRUE(slide.newton.lineSearch);             // this phase only
  EXPECT_EQ(slide.cutback.maxCutbacks, 2);          // this phase only
  EXPECT_EQ(slide.cutback.factor, 0.25);            // sticky from `cutback`
}

TEST(DeckParser, DefaultsEqualTheProblemSpecDefaults) {
  const ProblemSpec spec = parseDeckText(kMinimalDeck, virtualDeckPath());
  ASSERT_EQ(spec.phases.size(), 1u);
  const NewtonSpec expectedNewton;
  const CutbackSpec expectedCutback;
  const PhaseSpec& phase = spec.phases[0];
  EXPECT_EQ(phase.newton.maxIterations, expectedNewton.maxIterations);
  EXPECT_EQ(phase.newton.residualTolerance, expectedNewton.residualTolerance);
  EXPECT_EQ(phase.newton.energyTolerance, expectedNewton.energyTolerance);
  EXPECT_EQ(phase.newton.criterion, expectedNewton.criterion);
  EXPECT_EQ(phase.newton.divergenceFactor, expectedNewton.divergenceFactor);
  EXPECT_EQ(phase.newton.lineSearch, expectedNewton.lineSearch);
  EXPECT_EQ(phase.cutback.maxCutbacks, expectedCutback.maxCutbacks);
  EXPECT_EQ(phase.cutback.factor, expectedCutback.factor);
  EXPECT_EQ(phase.cutback.growAfter, expectedCutback.growAfter);
  EXPECT_EQ(phase.cutback.easyIterations, expectedCutback.easyIterations);
  EXPECT_EQ(phase.cutback.growFactor, expectedCutback.growFactor);
  EXPECT_EQ(phase.outputEvery, PhaseSpec{}.outputEvery);
  EXPECT_TRUE(spec.output.file.empty());  // the app derives it from the deck name

  // An `output` line without parameters means the same as no `output` line.
  const ProblemSpec withOutput = parseDeckText(kMinimalDeck + "output\n", virtualDeckPath());
  const OutputSpec defaults;
  for (const ProblemSpec* parsed : {&spec, &withOutput}) {
    EXPECT_EQ(parsed->output.displacement, defaults.displacement);
    EXPECT_EQ(parsed->output.reaction, defaults.reaction);
    EXPECT_EQ(parsed->output.stress, defaults.stress);
    EXPECT_EQ(parsed->output.contact, defaults.contact);
    EXPECT_EQ(parsed->output.csv, defaults.csv);
    EXPECT_EQ(parsed->output.xdmf, defaults.xdmf);
  }
  const ElementBlockSpec blockDefaults;
  EXPECT_EQ(spec.elementBlocks[0].thicknessAxis, blockDefaults.thicknessAxis);
  EXPECT_EQ(spec.elementBlocks[0].easParameters, blockDefaults.easParameters);
}

TEST(DeckParser, AbbreviationsAndCaseInsensitivity) {
  const std::string deck = R"deck(TITL "abbreviated"
MESH "meshes/cube.geo"
Mate Steel SVK e=200 NU=0.3
elem cube HEX8 MATE=Steel
rigi tool SPHE radi=0.5
fix bottom ALL
pres top UZ "0.1*t"
cont STAS mast=top slav=tool EPS_N=1 tang=exac
outp fiel=disp,REAC,cont CSV=No xdmf=TRUE
solv
NEWT maxi=5 conv=eith line=yes
cutb grow_a=2 grow_f=1.5 EASY=4
STEP 2 dt=0.5 resi=1e-6
End
)deck";
  const ProblemSpec spec = parseDeckText(deck, virtualDeckPath());
  EXPECT_EQ(spec.title, "abbreviated");
  ASSERT_EQ(spec.materials.size(), 1u);
  EXPECT_EQ(spec.materials[0].name, "Steel");  // user names keep their case
  EXPECT_EQ(spec.materials[0].youngsModulus, 200.0);
  EXPECT_EQ(spec.elementBlocks[0].material, "Steel");
  EXPECT_EQ(spec.rigidSurfaces[0].shape, RigidSurfaceSpec::Shape::Sphere);
  EXPECT_EQ(spec.rigidSurfaces[0].radius, 0.5);
  EXPECT_EQ(spec.fixes[0].components, (std::array<bool, 3>{true, true, true}));
  EXPECT_EQ(spec.prescribed[0].components[2]->expression, "0.1*t");
  EXPECT_EQ(spec.contacts[0].kind, ContactSpec::Kind::SegmentToAnalytical);
  EXPECT_EQ(spec.contacts[0].master, "top");
  EXPECT_EQ(spec.contacts[0].tangentMode, ContactSpec::TangentMode::Exact);
  EXPECT_TRUE(spec.output.displacement && spec.output.reaction && spec.output.contact);
  EXPECT_FALSE(spec.output.stress || spec.output.csv);
  EXPECT_TRUE(spec.output.xdmf);
  ASSERT_EQ(spec.phases.size(), 1u);
  EXPECT_EQ(spec.phases[0].steps, 2);
  EXPECT_EQ(spec.phases[0].newton.maxIterations, 5);
  EXPECT_EQ(spec.phases[0].newton.criterion, NewtonSpec::Criterion::Either);
  EXPECT_TRUE(spec.phases[0].newton.lineSearch);
  EXPECT_EQ(spec.phases[0].newton.residualTolerance, 1e-6);
  EXPECT_EQ(spec.phases[0].cutback.growAfter, 2);
  EXPECT_EQ(spec.phases[0].cutback.growFactor, 1.5);
  EXPECT_EQ(spec.phases[0].cutback.easyIterations, 4);
}

TEST(DeckParser, CommentsContinuationsAndLocations) {
  const std::string deck =
      "! FEAP-style comment\n"
      "mesh \"meshes/cube.geo\"   # trailing comment\n"
      "material steel svk &\n"
      "\n"
      "   # a comment line inside a continued line\n"
      "    E=200 \\\n"
      "    nu=0.3  ! another comment\n"
      "elements cube hex8 material=steel\n"
      "prescribe top uz \"1 # not a comment ! inside a string\"\n"
      "solve\n"
      "\tsteps 3 dt=0.25\r\n"
      "end";  // no final newline
  const ProblemSpec spec = parseDeckText(deck, virtualDeckPath());
  ASSERT_EQ(spec.materials.size(), 1u);
  EXPECT_EQ(spec.materials[0].youngsModulus, 200.0);
  EXPECT_EQ(spec.materials[0].poissonRatio, 0.3);
  EXPECT_EQ(spec.materials[0].where.line, 3);
  EXPECT_EQ(spec.prescribed[0].components[2]->expression, "1 # not a comment ! inside a string");
  EXPECT_EQ(spec.phases[0].steps, 3);
  EXPECT_EQ(spec.phases[0].where.line, 11);
  EXPECT_EQ(spec.phases[0].where.column, 2);  // after the tab
}

TEST(DeckParser, NumberFormatsFollowC) {
  struct Case {
    const char* text;
    double value;
  };
  const Case accepted[] = {{"2.1e4", 2.1e4},   {"-7.0E-3", -7.0e-3}, {".5", 0.5},
                           {"1.", 1.0},        {"+3", 3.0},          {"0x1p-2", 0.25},
                           {"1e-300", 1e-300}, {"-0", 0.0},          {"007", 7.0}};
  for (const Case& c : accepted) {
    double value = -1;
    EXPECT_EQ(deck::parseNumberText(c.text, value), "") << c.text;
    EXPECT_EQ(value, c.value) << c.text;
  }
  const std::pair<const char*, const char*> rejected[] = {
      {"2.1e4x", "'2.1e4x' is not a valid number (unexpected 'x' after '2.1e4')"},
      {"1e", "'1e' is not a valid number (unexpected 'e' after '1')"},
      {"1.2.3", "'1.2.3' is not a valid number (unexpected '.3' after '1.2')"},
      {"abc", "'abc' is not a number"},
      {"--1", "'--1' is not a number"},
      {"inf", "'inf' is not a finite number"},
      {"nan", "'nan' is not a finite number"},
      {"1e999", "'1e999' is not a finite number"}};
  for (const auto& [text, message] : rejected) {
    double value = 0;
    EXPECT_EQ(deck::parseNumberText(text, value), message);
  }
  long long integer = 0;
  EXPECT_EQ(deck::parseIntegerText("+12", integer), "");
  EXPECT_EQ(integer, 12);
  EXPECT_EQ(deck::parseIntegerText("-3", integer), "");
  EXPECT_EQ(integer, -3);
  EXPECT_EQ(deck::parseIntegerText("2.5", integer), "'2.5' is not an integer");
  EXPECT_EQ(deck::parseIntegerText("1e3", integer), "'1e3' is not an integer");
  EXPECT_EQ(deck::parseIntegerText("99999999999", integer),
            "'99999999999' is too large for an integer");

  // The same rules inside a deck, including hex floats and signs in vectors and tables.
  const ProblemSpec spec =
      parseDeckText(kMinimalDeck +
                        "material alt svk E=0x1.8p1 nu=-.125\n"
                        "rigid tool plane origin=( -1. , +.5 ,2e0 ) normal=(0,0,1)\n"
                        "prescribe top ux table (0,0) (0.5,-7.0E-3) (1e0,.5)\n",
                    virtualDeckPath());
  EXPECT_EQ(spec.materials[1].youngsModulus, 3.0);
  EXPECT_EQ(spec.materials[1].poissonRatio, -0.125);
  EXPECT_EQ(spec.rigidSurfaces[0].origin, (Vec3{-1.0, 0.5, 2.0}));
  EXPECT_EQ(spec.prescribed[0].components[0]->table,
            (std::vector<std::pair<double, double>>{{0, 0}, {0.5, -7e-3}, {1, 0.5}}));
}

TEST(DeckParser, TangentPresetsMapOntoParts) {
  auto partsOf = [](const std::string& option) {
    const ProblemSpec spec =
        parseDeckText(kMinimalDeck + "contact sts master=top slave=bottom eps_n=1 " + option + "\n",
                      virtualDeckPath());
    return spec.contacts.at(0);
  };
  const ContactSpec full = partsOf("tangent=full");
  EXPECT_EQ(full.tangentMode, ContactSpec::TangentMode::Paper);
  EXPECT_TRUE(full.parts.normalCurvature && full.parts.slideUnsymmetricCurvature);
  const ContactSpec main = partsOf("tangent=main");
  EXPECT_TRUE(main.parts.normalMain && main.parts.stickMain && main.parts.slideConstitutive);
  EXPECT_FALSE(main.parts.normalRotational || main.parts.normalCurvature ||
               main.parts.stickRotational || main.parts.stickCurvature ||
               main.parts.slideRotational || main.parts.slideCurvature ||
               main.parts.slideUnsymmetricCurvature);
  const ContactSpec exact = partsOf("tangent=exact");
  EXPECT_EQ(exact.tangentMode, ContactSpec::TangentMode::Exact);
  const ContactSpec listed =
      partsOf("parts=slide_unsymmetric_curvature,normal_rotational,stick_curvature");
  EXPECT_TRUE(listed.parts.slideUnsymmetricCurvature && listed.parts.normalRotational &&
              listed.parts.stickCurvature);
  EXPECT_FALSE(listed.parts.normalMain || listed.parts.stickMain || listed.parts.slideConstitutive);
}

TEST(DeckParser, BlocksMayComeInAnyOrder) {
  const std::string deck =
      "solve\n steps 1 dt=1\nend\n"
      "contact stas master=top slave=tool eps_n=1\n"  // the rigid surface comes later
      "elements cube hex8 material=steel\n"           // the material comes later
      "rigid tool plane normal=(0,0,-1) origin=(0,0,1.1)\n"
      "material steel svk E=200 nu=0.3\n"
      "mesh \"meshes/cube.geo\"\n";
  const ProblemSpec spec = parseDeckText(deck, virtualDeckPath());
  EXPECT_EQ(spec.contacts.at(0).slave, "tool");
  EXPECT_EQ(spec.elementBlocks.at(0).material, "steel");
  EXPECT_EQ(spec.rigidSurfaces.at(0).normal, (Vec3{0, 0, -1}));
}

// The first word after fix, prescribe and load is the SET, so `all` there is the built-in set of
// every node, also where `all` is fix's component word (`fix all all`: every component of every
// node). A component word in the SET's place still means the SET was left out.
TEST(DeckParser, TheFirstWordAllIsTheBuiltInSetOfEveryNode) {
  const ProblemSpec spec =
      parseDeckText(kMinimalDeck +
                        "fix all uz\nfix all all\nfix top all\nprescribe all ux \"0.1*t\"\n"
                        "load all fy 2\n",
                    virtualDeckPath());
  ASSERT_EQ(spec.fixes.size(), 4u);
  EXPECT_EQ(spec.fixes[1].set, "all");
  EXPECT_EQ(spec.fixes[1].components, (std::array<bool, 3>{false, false, true}));
  EXPECT_EQ(spec.fixes[2].set, "all");
  EXPECT_EQ(spec.fixes[2].components, (std::array<bool, 3>{true, true, true}));
  EXPECT_EQ(spec.fixes[3].set, "top");
  EXPECT_EQ(spec.fixes[3].components, (std::array<bool, 3>{true, true, true}));
  EXPECT_EQ(spec.prescribed.at(0).set, "all");
  EXPECT_EQ(spec.loads.at(0).set, "all");
  EXPECT_NE(std::string(parseError(kMinimalDeck + "fix all\n").what())
                .find(":8:8: error: fix 'all': give the fixed components: 'fix all' names the "
                      "built-in set of every node but no component"),
            std::string::npos);
  EXPECT_NE(std::string(parseError(kMinimalDeck + "fix uz\n").what())
                .find(":8:5: error: fix: missing SET before 'uz'"),
            std::string::npos);
}

}  // namespace
}  // namespace cc::test
