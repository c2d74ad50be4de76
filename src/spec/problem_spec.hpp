// ProblemSpec: the validated, plain-data result of parsing a deck. Owns nothing but values; every
// item carries the SourceLocation it came from so that later stages (model building, mesh checks)
// can still report "file:line: what was expected". Downstream code never sees deck text.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/source_location.hpp"

namespace cc {

using Vec3 = std::array<double, 3>;

// A scalar function of time (and, for prescribed displacements, of the reference position x,y,z).
// Either a muParser expression or a piecewise-linear table (constant beyond its ends).
struct FunctionSpec {
  enum class Kind { Expression, Table };
  Kind kind = Kind::Expression;
  std::string expression;                        // Kind::Expression, variables t, x, y, z
  std::vector<std::pair<double, double>> table;  // Kind::Table, (t, value), t strictly increasing
  SourceLocation where;
};

struct MeshSpec {
  std::string path;                          // absolute, resolved against the deck's directory
  std::map<std::string, double> parameters;  // .geo only: gmsh -setnumber NAME VALUE
  SourceLocation where;
};

struct MaterialSpec {
  enum class Model { StVenantKirchhoff, NeoHooke, NeoHookeDecoupled };
  std::string name;
  Model model = Model::StVenantKirchhoff;
  double youngsModulus = 0;
  double poissonRatio = 0;
  SourceLocation where;
};

struct ElementBlockSpec {
  enum class Type { Hex8, SolidShell8, SolidShell18 };
  std::string group;  // gmsh physical volume group name
  Type type = Type::Hex8;
  std::string material;  // MaterialSpec::name
  // Solid-shells: thickness direction. -1 = from the node ordering (the mesh's extrusion
  // direction, local zeta), 0/1/2 = the element's local axis closest to global x/y/z.
  int thicknessAxis = -1;
  int easParameters = 1;  // SolidShell8/18: number of EAS thickness-strain parameters
  SourceLocation where;
};

// The built-in node set of every node of the mesh (`fix all uz` for plane strain). It is the
// first word after `fix`, `prescribe` and `load`, so it never clashes with the component word
// of `fix SET all`; a physical group may therefore not be named `all` (refused by the mesh).
inline constexpr const char* kAllNodesSet = "all";

struct FixSpec {
  std::string set;
  std::array<bool, 3> components{false, false, false};  // ux, uy, uz
  SourceLocation where;
};

// Prescribed displacement components on a node set; unset components stay free.
struct PrescribeSpec {
  std::string set;
  std::array<std::optional<FunctionSpec>, 3> components;
  SourceLocation where;
};

// Nodal forces on a node set. `total` splits the value equally over the set's nodes.
struct LoadSpec {
  std::string set;
  std::array<std::optional<FunctionSpec>, 3> components;
  bool total = false;
  SourceLocation where;
};

// A rigid analytic surface (the "slave" of an STAS pair in the paper's terminology, section 6.3.1).
struct RigidSurfaceSpec {
  enum class Shape { Plane, Cylinder, ParabolicCylinder, Sphere };
  std::string name;
  Shape shape = Shape::Plane;
  Vec3 origin{0, 0, 0};  // plane point / cylinder axis point / parabola vertex / sphere centre
  Vec3 normal{0, 0, 1};  // plane normal (towards the deformable body); parabola opening direction
  Vec3 axis{0, 1, 0};    // cylinder and parabolic cylinder axis (generatrix direction)
  double radius = 0;     // cylinder, sphere
  double curvature = 0;  // parabolic cylinder: z = c x^2 in its local frame (c = curvature)
  std::array<std::optional<FunctionSpec>, 3> motion;  // rigid translation u(t)
  SourceLocation where;
};

// Which parts of the paper's tangent (Tables 1 and 2) are assembled. The residual never
// depends on these flags.
struct TangentPartsSpec {
  bool normalMain = true;                 // eq. (83)
  bool normalRotational = true;           // eq. (83a)
  bool normalCurvature = true;            // eq. (83b)
  bool stickMain = true;                  // eq. (100)
  bool stickRotational = true;            // eq. (100a)
  bool stickCurvature = true;             // eq. (100b)
  bool slideConstitutive = true;          // eqs. (107), (107a), (107b)
  bool slideRotational = true;            // eq. (107c)
  bool slideCurvature = true;             // eq. (107d)
  bool slideUnsymmetricCurvature = true;  // eq. (107e)
};

struct ContactSpec {
  enum class Kind { SegmentToSegment, NodeToSegment, SegmentToAnalytical };
  // Paper: the parts of Tables 1-2. Exact: linearization of the discrete algorithm itself.
  enum class TangentMode { Paper, Exact };
  std::string name;  // pair name used in output (default "pair<k>")
  Kind kind = Kind::SegmentToSegment;
  std::string master;  // face set (STS/NTS); for STAS the deformable body's face set
  std::string slave;   // face set (STS), node or face set (NTS); rigid surface name (STAS)
  // Penalty: a plain penalty as in the paper; Augmented: augmented Lagrangian (Uzawa updates
  // of the normal and tangential multipliers per load step, contact/augmentation.cpp).
  enum class Enforcement { Penalty, Augmented };
  double penaltyNormal = 0;      // eps_N; 0 = automatic (automatic_penalty.cpp)
  double penaltyTangential = 0;  // eps_T; 0 with mu > 0 = automatic
  double penaltyScale = 1;       // factor on the automatic penalties (eps_scale=)
  Enforcement enforcement = Enforcement::Penalty;
  double augmentationTolerance = 1e-3;  // aug_tol: integrated multiplier update / contact force
  int maxAugmentations = 100;           // aug_max: Uzawa updates per step before giving up
  int accelerationDepth = 5;            // aug_depth: Anderson depth of the updates (0: plain)
  bool growPenalty = true;              // aug_grow: raise a soft penalty when the updates stall
  double friction = 0;                  // mu >= 0; mu = 0 computes no tangential terms
  int integrationPoints = 2;            // Gauss points per direction (STS, STAS)
  TangentMode tangentMode = TangentMode::Paper;
  TangentPartsSpec parts;
  // Faceted: the master segments' own interpolation, as in the paper. Smooth: Nagata patches
  // over nodal normals (contact/nagata.hpp; sts and nts with Quad4 masters), issue 16 part 2.
  enum class MasterSurface { Faceted, Smooth };
  MasterSurface masterSurface = MasterSurface::Faceted;
  // Smooth: edges across which the facets turn by more than this stay sharp (crease=, degrees).
  double creaseDegrees = 30;
  // Sharp: a slave point beyond the master's free edge (by more than 1% of the half segment) has
  // no contact force, as in the paper. Fade: the force falls smoothly to zero over a band of 10%
  // of the segment beyond it (contact/contact_point.hpp, kFreeEdgeBand; issue 14).
  enum class MasterEdge { Sharp, Fade };
  MasterEdge masterEdge = MasterEdge::Sharp;
  // STS only. Gauss: integrationPoints^2 Gauss points per slave segment, as in the paper.
  // Segments: points on the pieces of each slave segment's overlap with the master segments,
  // rebuilt every step (contact/segmentation.hpp), issue 16 part 1.
  enum class Integration { Gauss, Segments };
  Integration integration = Integration::Gauss;
  SourceLocation where;
};

struct NewtonSpec {
  enum class Criterion { Energy, Residual, Both, Either };
  int maxIterations = 30;
  double residualTolerance = 1e-10;  // ||R_k|| / ||R_0||
  double energyTolerance = 1e-16;    // |du_k . R_k| / |du_0 . R_0| (FEAP's default)
  Criterion criterion = Criterion::Energy;
  double divergenceFactor = 1e6;  // ||R_k|| > factor * ||R_0|| counts as divergence
  bool lineSearch = false;
  // Whether the deck set line_search. If not, a deck with an enforcement=augmented contact pair
  // gets the line search (deck/solve_keywords.cpp, resolveNewtonDefaults): each Uzawa update
  // moves the contact forces by eps g, and at a stiff penalty plain Newton then cycles.
  bool lineSearchChosen = false;
  // The first iterate of a step (issue 14). Prescribed: the converged state, the prescribed
  // increment entering linearly (K_fp du_p, FEAP's predictor; the paper decks' counts).
  // Extrapolate: the converged state plus the last converged step's increment scaled to this
  // step's dt (a constant-velocity predictor, as the established code of issue 14 starts each
  // increment), on every dof; what the prescribed values still differ by enters linearly.
  enum class Predictor { Prescribed, Extrapolate };
  Predictor predictor = Predictor::Prescribed;
  // A step that fails with and without line search at a contact penalty far above its
  // automatic value is retried by solves at growing penalties, starting from the automatic one
  // (solver/load_stepper.cpp).
  bool penaltyContinuation = true;
  // Augmented Lagrangian (issue 16, 3a): 0 re-solves every multiplier update to the full
  // criterion (Uzawa per converged step). A fraction rho in (0, 1) makes the updates interleave
  // with Newton iterations instead: a re-solve stops once its residual has fallen to rho times its
  // own first one, the multipliers are updated from that iterate, and only when the update rule
  // is met there is the step solved to the full criterion and the rule checked again
  // (LoadStepper::augmentStep). rho = 0.1 saves 30-40 % of the Newton iterations (up to 10
  // eps_ref) but leaves the results less far inside the rule's tolerance
  // (docs/verification/augmented_lagrangian.md): not the default. Without multipliers (penalty
  // pairs only) it has no effect.
  double augmentedInnerTolerance = 0;
  // Viscous stabilisation (deck: `newton stabilize=C`; off at 0): every solid node carries the
  // artificial viscous force C m (x - x_n) / dt, with m its share of the elements' volumes (a
  // lumped mass of unit density) and x_n its place at the last converged step. It makes the
  // tangent regular where the quasi-static problem has none (a body held by contact alone
  // before it touches, a fold of the frictional problem: docs/verification/sliding.md), at
  // the price of a rate-dependent force whose work the energy balance reports as
  // `stabilization_dissipation`. The same role as Abaqus's *STATIC, STABILIZE with a factor.
  double stabilization = 0;
  // The factor chosen by the run instead (deck: `stabilize_share=F`; off at 0): the phase's
  // first step is solved without stabilisation, and C is then set for the rest of the phase
  // so that a step like that one would dissipate the fraction F of its work of the loads and
  // supports, C = F |W| dt / sum_a m_a |x_a - x_n,a|^2 (LoadStepper). The share is the
  // quantity the run reports step by step, so the knob and the report are one number. Abaqus
  // and ANSYS measure their fraction against the strain energy instead; in steady sliding that
  // hardly changes from step to step (the work goes into friction), so it cannot set a factor
  // for a phase that starts there. Never set together with `stabilization` (the deck keeps
  // the last one given).
  double stabilizationShare = 0;
  // Stabilisation only where steps need it (deck: `stabilize_on_failure=C`; off at 0): a step
  // whose attempt fails without it (after its line-search retry) is solved again at the same
  // step size with the factor C, and its cut-backs and the next steps keep it until grow_after
  // of them in a row converged easily (LoadStepper::solveStabilized). A run need not know where
  // its fold lies, and the steps before it keep the quasi-static answer exactly. Never set
  // together with the two above.
  double stabilizationOnFailure = 0;
  // The same with the factor chosen by the run (deck: `stabilize_on_failure_share=F`; off at 0):
  // after every step that converged without stabilisation, C is set so that a step like it
  // would dissipate the fraction F of its work of the loads, supports and moving rigid surfaces (as
  // for stabilizationShare), and a failing step is stabilised with the last such C
  // (LoadStepper::measureFailureFactor). The factor C depends on the model's units, masses and
  // speeds; the share does not, so one value serves a mesh refined or a model rescaled. Never
  // set together with the three above.
  double stabilizationOnFailureShare = 0;
};

// The linear solver of the Newton systems (deck: `solve solver=...`, issue 13). Auto keeps the
// direct pair (CHOLMOD for symmetric positive definite tangents, UMFPACK otherwise) below a
// measured break-even size and uses the iterative PETSc backend above it; Cholmod is that pair
// at every size (CHOLMOD cannot factor an unsymmetric tangent). The others force one backend:
// UMFPACK alone, MUMPS or SuperLU_dist (direct, through PETSc), hypre BoomerAMG or PETSc's GAMG
// preconditioning GMRES.
struct LinearSolverSpec {
  enum class Method { Auto, Cholmod, Umfpack, Mumps, SuperluDist, Amg, Gamg };
  Method method = Method::Auto;
  // CHOLMOD's and UMFPACK's factors serve later tangents of a Newton solve as GMRES
  // preconditioners (solver/factor_reuse.hpp); `solve reuse_factor=no` factorizes every
  // tangent. Default: yes, except in a deck with an augmented-Lagrangian pair (deck layer).
  bool reuseFactor = true;
  bool reuseFactorChosen = false;  // given in the deck
  SourceLocation where;
};

struct CutbackSpec {
  int maxCutbacks = 10;  // per step, total halvings before the run stops
  double factor = 0.5;   // dt multiplier on failure
  int growAfter = 3;     // easy steps (iterations <= easyIterations) before regrowth
  int easyIterations = 6;
  double growFactor = 2.0;  // dt multiplier on regrowth, never beyond the phase's dt
};

// One phase of the solve block: `steps` load steps of size dt, each solved by Newton.
struct PhaseSpec {
  int steps = 1;
  double dt = 1.0;
  NewtonSpec newton;
  CutbackSpec cutback;
  int outputEvery = 1;  // write every k-th converged step (the phase's last step always)
  SourceLocation where;
};

struct OutputSpec {
  std::string file;  // HDF5 path; empty = <deck basename>.h5 in the working directory
  bool displacement = true;
  bool reaction = true;
  bool stress = false;
  bool contact = true;
  bool csv = true;   // <file stem>_reactions.csv
  bool xdmf = true;  // <file stem>.xdmf
  SourceLocation where;
};

// A value to compare a result against (issue 6). `quantity` names an output, e.g.
// "reaction:top:z" or "contact:pair1:force:z"; the reference is a number, a table over time,
// or a named analytic solution with parameters.
struct ReferenceSpec {
  std::string quantity;
  std::optional<double> value;
  std::vector<std::pair<double, double>> table;
  std::string analytic;                      // e.g. "hertz_sphere"
  std::map<std::string, double> parameters;  // of the analytic solution
  SourceLocation where;
};

struct ProblemSpec {
  std::string title;
  std::string deckPath;  // as given on the command line
  std::string deckText;  // the main deck's text followed by every included file's text
  std::vector<std::string> deckFiles;  // the deck and every file it includes (absolute paths)
  MeshSpec mesh;
  std::vector<MaterialSpec> materials;
  std::vector<ElementBlockSpec> elementBlocks;
  std::vector<FixSpec> fixes;
  std::vector<PrescribeSpec> prescribed;
  std::vector<LoadSpec> loads;
  std::vector<RigidSurfaceSpec> rigidSurfaces;
  std::vector<ContactSpec> contacts;
  std::vector<PhaseSpec> phases;
  LinearSolverSpec linearSolver;
  OutputSpec output;
  std::vector<ReferenceSpec> references;

  // Whether a contact pair is enforced by the augmented Lagrangian (the Newton defaults and the
  // run header depend on it).
  bool hasAugmentedContact() const {
    for (const ContactSpec& contact : contacts) {
      if (contact.enforcement == ContactSpec::Enforcement::Augmented) return true;
    }
    return false;
  }
};

}  // namespace cc
