// The deck's keywords, each declared once: arguments, parameters with types, defaults, ranges
// and descriptions, clauses, and the handler that turns a parsed line into ProblemSpec items.
#include <fmt/format.h>

#include "deck/deck_state.hpp"
#include "deck/keyword_decl.hpp"
#include "deck/solve_parameters.hpp"
#include "deck/spec_choices.hpp"

namespace cc::deck {

namespace {

using Argument = ClauseDecl::Argument;
using Block = KeywordDecl::Block;

// Gauss points per direction on a contact segment: the largest Gauss-Legendre rule that
// fem/quadrature.hpp provides (kMaxGaussPoints; a deck unit test keeps the two equal).
constexpr double kMaxContactGaussPoints = 6;

// The SET of fix, prescribe and load (kAllNodesSet: `all` is read as the set there, also in
// `fix all uz`, where it is the first word and the component word `all` cannot stand).
constexpr const char* kNodeSetDescription =
    "gmsh physical group (its nodes), or `all`: every node of the mesh";

std::vector<ClauseDecl> componentClauses(const std::vector<std::string>& components,
                                         Argument argument, const std::string& what) {
  std::vector<ClauseDecl> clauses;
  const char* axes[] = {"x", "y", "z"};
  for (std::size_t i = 0; i < components.size(); ++i) {
    clauses.push_back({components[i], argument, fmt::format("{} in {}", what, axes[i])});
  }
  return clauses;
}

KeywordDecl includeKeyword() {
  return {.name = "include",
          .block = Block::Source,
          .summary = "Reads the lines of another file in place of this line.",
          .positionals = {stringValue("PATH", "file to include, relative to this file")},
          .notes =
              "Includes may be nested; a file that includes itself, directly or through "
              "other files, is an error that names the cycle."};
}

KeywordDecl titleKeyword() {
  return {.name = "title",
          .summary = "Title of the run, stored in the results file.",
          .positionals = {stringValue("TEXT", "title text")},
          .handler = handleTitle};
}

KeywordDecl meshKeyword() {
  return {.name = "mesh",
          .summary = "The gmsh mesh: a .msh file, or a .geo file meshed when the run starts.",
          .positionals = {stringValue("PATH", "a .msh or .geo file, relative to this file")},
          .extraNumbers = "for a .geo file: gmsh variables, as `gmsh -setnumber NAME NUMBER`",
          .notes =
              "Physical volume groups name element blocks, physical surface groups name "
              "face sets; every physical group also names the node set of its nodes.",
          .handler = handleMesh};
}

KeywordDecl materialKeyword() {
  return {
      .name = "material",
      .summary = "A named hyperelastic material.",
      .positionals = {identifierValue("NAME", "material name, used by `elements material=`"),
                      enumValue(
                          "MODEL", choiceNames(materialModels()),
                          "St. Venant-Kirchhoff, compressible neo-Hooke, or decoupled neo-Hooke "
                          "(Abaqus/CalculiX form)")},
      .parameters =
          {numberValue("E", "Young's modulus").withRange(Range::greaterThan(0)).asRequired(),
           numberValue("nu", "Poisson's ratio")
               .withRange(Range::between(-1, false, 0.5, false))
               .asRequired()},
      .itemName = "NAME",
      .handler = handleMaterial};
}

KeywordDecl elementsKeyword() {
  return {
      .name = "elements",
      .summary = "Element formulation and material of one physical volume group.",
      .positionals = {identifierValue("GROUP", "gmsh physical volume group"),
                      enumValue("TYPE", choiceNames(elementTypes()),
                                "trilinear brick, 8-node or 18-node solid-shell")},
      .parameters = {identifierValue("material", "name of a `material`").asRequired(),
                     enumValue("thickness", choiceNames(thicknessAxes()),
                               "solid-shells: thickness direction; auto = the mesh's extrusion "
                               "direction (local zeta), x|y|z = the local axis closest to it")
                         .withDefault("auto"),
                     integerValue("eas",
                                  "solid-shells: enhanced-strain (EAS) parameters. solid_shell8: "
                                  "0 none; 1 thickness strain E33~zeta; 3 E33~zeta(1,xi,eta); "
                                  "5/7 = 1/3 plus in-plane modes E11~xi, E22~eta, E12~xi,eta "
                                  "(in-plane bending and near incompressibility, like an "
                                  "incompatible-mode brick). solid_shell18: 0, 1, 3, or 9 "
                                  "(E33~zeta x biquadratic). See docs/verification/shells.md")
                         .withRange(Range::atLeast(0))
                         .withDefault("1")},
      .itemName = "GROUP",
      .notes = "`thickness=` and `eas=` apply to solid-shell elements only.",
      .handler = handleElements};
}

KeywordDecl fixKeyword() {
  std::vector<ClauseDecl> clauses =
      componentClauses(kDisplacementComponents, Argument::None, "fix the displacement");
  clauses.push_back({"all", Argument::None, "fix all three displacements"});
  return {.name = "fix",
          .summary = "Zero displacement components on a node set.",
          .positionals = {nodeSetValue("SET", kNodeSetDescription)},
          .clauses = clauses,
          .itemName = "SET",
          .notes =
              "The first word is always the SET: `fix all uz` fixes uz of every node (plane "
              "strain), `fix all all` clamps every node, `fix SET all` all components of SET. "
              "`fix all` alone is an error (no component). A physical group may not be named "
              "`all`. Fixing a dof twice (sets sharing an edge) is accepted; for a fixed dof "
              "that is also prescribed see `prescribe`.",
          .handler = handleFix};
}

KeywordDecl prescribeKeyword() {
  return {.name = "prescribe",
          .summary = "Prescribed displacement components on a node set, as functions of time.",
          .positionals = {nodeSetValue("SET", kNodeSetDescription)},
          .clauses = componentClauses(kDisplacementComponents, Argument::Function, "displacement"),
          .itemName = "SET",
          .notes =
              "A FUNCTION is a quoted muParser expression in t, x, y, z (x, y, z: the "
              "node's reference position), a plain number, or `table (t,v) (t,v) ...`: "
              "piecewise linear with strictly increasing t, constant beyond its ends. "
              "Components not named stay free. A dof may carry two conditions (overlapping "
              "sets, or `fix` and `prescribe`) only if both give the same value (a fixed dof: 0) "
              "at every time the run evaluates them: they are compared at t = 0 and at every "
              "step end and step midpoint of the solve block before the run (the deck is "
              "refused naming both lines), and at any other time a cut-back reaches when the "
              "run gets there (the run stops with the same message and keeps its converged "
              "steps).",
          .handler = handlePrescribe};
}

KeywordDecl loadKeyword() {
  std::vector<ClauseDecl> clauses =
      componentClauses(kForceComponents, Argument::Function, "nodal force");
  clauses.push_back(
      {"total", Argument::None,
       "the FUNCTION values are the set's total force, split equally over its nodes"});
  return {.name = "load",
          .summary = "Nodal forces on a node set, as functions of time (and position).",
          .positionals = {nodeSetValue("SET", kNodeSetDescription)},
          .clauses = clauses,
          .itemName = "SET",
          .notes = "Without `total` every node of the set receives the full value.",
          .handler = handleLoad};
}

KeywordDecl rigidKeyword() {
  return {
      .name = "rigid",
      .summary = "A rigid analytic surface, the slave of an `stas` contact pair.",
      .positionals = {identifierValue("NAME", "surface name, used by `contact stas slave=`"),
                      enumValue("SHAPE", choiceNames(rigidShapes()), "surface shape")},
      .parameters =
          {vectorValue("origin",
                       "plane point, cylinder axis point, parabola vertex or sphere "
                       "centre")
               .withDefault("(0,0,0)"),
           vectorValue("normal",
                       "plane: normal towards the deformable body; "
                       "parabolic_cylinder: opening direction"),
           vectorValue("axis", "cylinder and parabolic_cylinder: generatrix direction"),
           numberValue("radius", "cylinder and sphere radius").withRange(Range::greaterThan(0)),
           numberValue("c", "parabolic_cylinder: z = c x^2 in its local frame")},
      .clauses = componentClauses(kDisplacementComponents, Argument::Function, "rigid translation"),
      .itemName = "NAME",
      .notes =
          "Required per shape: plane `normal=`; cylinder `axis=` `radius=`; "
          "parabolic_cylinder `normal=` `axis=` (not parallel) `c=` (non-zero); sphere "
          "`radius=`. A parameter the shape does not use is an error. The motion clauses "
          "are functions of t only.",
      .handler = handleRigid};
}

KeywordDecl contactKeyword() {
  return {
      .name = "contact",
      .summary = "A contact pair with penalty regularization and Coulomb friction.",
      .positionals = {enumValue("KIND", choiceNames(contactKinds()),
                                "segment-to-segment, node-to-segment, or segment-to-analytical "
                                "(rigid) surface")},
      .parameters =
          {identifierValue("master",
                           "face set of the master surface (stas: the deformable "
                           "body's face set)")
               .asRequired(),
           identifierValue("slave", "face set (sts, nts) or `rigid` surface name (stas)")
               .asRequired(),
           numberValue("eps_n",
                       "normal penalty eps_N (omitted: automatic, from E/h of the adjacent "
                       "elements, see notes)")
               .withRange(Range::greaterThan(0)),
           numberValue("eps_t", "tangential penalty eps_T (omitted with mu > 0: automatic)")
               .withRange(Range::greaterThan(0)),
           numberValue("eps_scale", "factor on the automatic penalties")
               .withRange(Range::greaterThan(0))
               .withDefault("1"),
           enumValue("enforcement", choiceNames(contactEnforcements()),
                     "penalty as in the paper, or augmented Lagrangian (Uzawa updates per step)")
               .withDefault("penalty"),
           numberValue("aug_tol",
                       "augmented: stop when the multiplier updates, integrated over the surface, "
                       "are below aug_tol times the normal contact force")
               .withRange(Range::greaterThan(0))
               .withDefault("1e-3"),
           integerValue("aug_max", "augmented: Uzawa updates per step before the step fails")
               .withRange(Range::between(1, true, 10000, true))
               .withDefault("100"),
           integerValue("aug_depth",
                        "augmented: Anderson acceleration of the Uzawa updates, combining the "
                        "last aug_depth updates (0: plain Uzawa)")
               .withRange(Range::between(0, true, 50, true))
               .withDefault("5"),
           boolValue("aug_grow",
                     "augmented: when the updates stall (less than halved over 10 updates) "
                     "at a penalty below the automatic one, raise eps_n and eps_t tenfold, at "
                     "most to the automatic penalty, for the rest of the run")
               .withDefault("yes"),
           numberValue("mu", "Coulomb friction coefficient (0: frictionless)")
               .withRange(Range::atLeast(0))
               .withDefault("0"),
           integerValue("points", "sts, stas: Gauss points per direction on each segment")
               .withRange(Range::between(1, true, kMaxContactGaussPoints, true))
               .withDefault("2"),
           enumValue("tangent", choiceNames(tangentPresets()),
                     "tangent parts: all (full), without curvature parts, main parts only, or "
                     "the exact linearization")
               .withDefault("full"),
           enumListValue("parts", choiceNames(tangentParts()),
                         "explicit list of assembled tangent parts (instead of tangent=)"),
           enumValue("surface", choiceNames(masterSurfaces()),
                     "sts, nts: the master segments as meshed, or smoothed (Nagata patches "
                     "over nodal normals, Quad4 masters)")
               .withDefault("faceted"),
           numberValue("crease",
                       "surface=smooth: edges where the master's facets meet at more than this "
                       "angle (degrees) stay sharp, as meshed")
               .withRange(Range::between(0, false, 180, true))
               .withDefault("30"),
           enumValue("edge", choiceNames(masterEdges()),
                     "sts, nts: beyond the master's free edges no force (sharp), or a force "
                     "fading smoothly to zero over 10% of a segment (fade)")
               .withDefault("sharp"),
           enumValue("integration", choiceNames(contactIntegrations()),
                     "sts: points= Gauss points per direction on each slave segment (gauss), or "
                     "points on its pieces of overlap with the master segments (segments)")
               .withDefault("gauss"),
           identifierValue("name", "pair name in the output (default pairK for the K-th pair)")},
      .itemName = "name",
      .notes =
          "`tangent=no_curvature` drops normal_curvature, stick_curvature, "
          "slide_curvature and slide_unsymmetric_curvature; `tangent=main` keeps only "
          "normal_main, stick_main and slide_constitutive. Give `tangent=` or `parts=`, "
          "not both. The residual never depends on these choices. Automatic penalty: "
          "eps_N = eps_T = eps_scale * 10 * min over master and slave of the mean E/h of the "
          "elements behind the surface faces (h: twice the distance from a face centre to its "
          "element's centre along the face normal; stas: the master only); the values are "
          "printed at the start and stored with the pair's output. Whatever the penalty, a "
          "run whose deepest penetration (of points under the master: beside its free edges, "
          "in edge=fade's band, a gap measures nothing) exceeds a quarter of the mean h of the "
          "softer side says so at its end: a penalty that soft for the mesh changes the results "
          "(a fixed eps_n does not grow as the mesh is refined; the automatic one does). "
          "enforcement=augmented "
          "re-solves each step with updated multipliers lambda_N, lambda_T (N = min(0, "
          "lambda_N + eps_N g), friction cone on the augmented traction) until the updates "
          "(normal, and tangential at sticking points), integrated over the surface and "
          "weighted by max(1, eps_ref / eps) with eps_ref the automatic penalty, are below "
          "aug_tol times the normal contact force: the penetration left is at most aug_tol "
          "times the automatic penalty's, whatever eps. Each update combines the last "
          "aug_depth ones (Anderson acceleration). surface=smooth replaces each "
          "Quad4 master segment by its Nagata patch (quadratic edges orthogonal to the nodal "
          "normals, angle-weighted averages of the adjacent segments' normals in the "
          "converged configuration at the start of each step, held fixed over the step): "
          "search, projection, gap, normal, curvature and the tangent (exact for the fixed "
          "normals) then follow the C0 surface with continuous normals at the nodes "
          "(docs/verification/smooth_master.md); edges where the facets meet at more than "
          "crease= degrees stay sharp (straight, a normal on each side), so a tool's edges "
          "and corners keep their shape. integration=segments splits each slave "
          "segment, in its parameter plane, by the images of the master segments it overlaps "
          "(segmentation as in mortar methods) and puts a triangle rule on every piece "
          "(points=1, 2, 3 or more: 1, 3 or 7 points per triangle; an unsplit segment keeps "
          "its points x points Gauss rule); the points are rebuilt from the converged "
          "configuration at the start of every step and fixed over it, each taking over the "
          "history of the nearest old point; such a run cannot be restarted "
          "(docs/verification/segment_sts.md).",
      .handler = handleContact};
}

KeywordDecl outputKeyword() {
  return {
      .name = "output",
      .summary = "What the results file holds.",
      .parameters = {stringValue("file",
                                 "HDF5 results file (default: the deck's name "
                                 "with .h5, in the working directory)"),
                     enumListValue("fields", choiceNames(outputFields()),
                                   "fields written at every output step")
                         .withDefault("displacement,reaction,contact"),
                     boolValue("csv",
                               "also write the set reactions as STEM_reactions.csv (STEM: results "
                               "file name without .h5)")
                         .withDefault("yes"),
                     boolValue("xdmf", "also write STEM.xdmf beside the results file, for ParaView")
                         .withDefault("yes")},
      .handler = handleOutput};
}

KeywordDecl referenceKeyword() {
  return {.name = "reference",
          .summary = "A reference value for a result quantity; `covcontact run` reports its error.",
          .positionals = {stringValue("QUANTITY",
                                      "result quantity, e.g. reaction:top:z or "
                                      "contact:pair1:force:z")},
          .parameters = {numberValue("value", "constant reference value")},
          .clauses = {{"table", Argument::Points, "reference values over time"},
                      {"analytic", Argument::Identifier, "named analytic solution"}},
          .extraNumbers = "parameters of the `analytic` solution",
          .notes =
              "Give exactly one of `value=`, `table` or `analytic NAME`; NAME=NUMBER pairs "
              "are allowed only with `analytic`.",
          .handler = handleReference};
}

KeywordDecl solveKeyword() {
  return {.name = "solve",
          .summary = "Opens the solution block; its commands run in order until `end`.",
          .parameters = {enumValue("solver", choiceNames(linearSolverMethods()),
                                   "linear solver of the Newton systems: auto (cholmod below "
                                   "50 000 free equations, amg above), cholmod "
                                   "(CHOLMOD, UMFPACK for unsymmetric tangents), umfpack, "
                                   "mumps, superlu_dist (direct, PETSc), amg (GMRES + hypre "
                                   "BoomerAMG), gamg (GMRES + PETSc GAMG)")
                             .withDefault("auto"),
                         boolValue("reuse_factor",
                                   "solve a tangent by GMRES preconditioned by the CHOLMOD or "
                                   "UMFPACK factor of an earlier tangent of the same Newton "
                                   "solve, factorizing when that needs more than 40 iterations "
                                   "(no: factorize every tangent); default yes, no in a deck "
                                   "with an enforcement=augmented pair")},
          .notes = "A deck has exactly one solve block with at least one `steps` line.",
          .handler = handleSolve};
}

KeywordDecl endKeyword() {
  return {.name = "end",
          .block = Block::Solve,
          .summary = "Closes the solve block.",
          .handler = handleEnd};
}

KeywordDecl newtonKeyword() {
  return {.name = "newton",
          .block = Block::Solve,
          .summary = "Newton settings for this and all later phases (sticky).",
          .parameters = newtonParameters(),
          .notes =
              "Parameters not given keep their current value; the defaults shown are the "
              "values before any `newton` line.",
          .handler = handleNewton};
}

KeywordDecl cutbackKeyword() {
  return {.name = "cutback",
          .block = Block::Solve,
          .summary = "Automatic step cut-back settings for this and all later phases (sticky).",
          .parameters = cutbackParameters(),
          .notes =
              "Parameters not given keep their current value; the defaults shown are the "
              "values before any `cutback` line.",
          .handler = handleCutback};
}

KeywordDecl stepsKeyword() {
  std::vector<ValueDecl> parameters = {
      numberValue("dt", "time step size").withRange(Range::greaterThan(0)).asRequired(),
      integerValue("output_every",
                   "write every K-th converged step (the phase's last step "
                   "is always written)")
          .withRange(Range::atLeast(1))
          .withDefault("1")};
  for (const ValueDecl& parameter : phaseOnlyParameters()) parameters.push_back(parameter);
  return {.name = "steps",
          .block = Block::Solve,
          .summary = "A phase of N load steps of size dt, each solved by Newton's method.",
          .positionals = {integerValue("N", "number of steps").withRange(Range::atLeast(1))},
          .parameters = parameters,
          .notes =
              "Newton and cut-back parameters on a `steps` line apply to this phase only "
              "and override the sticky `newton`/`cutback` settings; on a `steps` line the "
              "cut-back `max=` and `factor=` are spelled `cutback_max=` and "
              "`cutback_factor=`.",
          .handler = handleSteps};
}

}  // namespace

const std::vector<KeywordDecl>& keywordTable() {
  static const std::vector<KeywordDecl> table = {
      includeKeyword(), titleKeyword(),     meshKeyword(),  materialKeyword(), elementsKeyword(),
      fixKeyword(),     prescribeKeyword(), loadKeyword(),  rigidKeyword(),    contactKeyword(),
      outputKeyword(),  referenceKeyword(), solveKeyword(), newtonKeyword(),   cutbackKeyword(),
      stepsKeyword(),   endKeyword()};
  return table;
}

}  // namespace cc::deck
