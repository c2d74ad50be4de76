"""The narrative of docs/verification/accuracy.md: how the errors are measured, what limits each
case's accuracy and the recommended settings (the tables and plots are generated from the runs
by accuracy_report.py; the numbers quoted here were read from them)."""

INTRODUCTION = """# Accuracy against run time: contact verification

This page is written by `scripts/error_vs_time.py` (run it with `/usr/bin/python3`; it reuses
finished runs from `build-verif/accuracy/results.json`). It answers the question users ask when
they choose a mesh, a load-step size, a penalty and a contact kind: *how accurate is the result
and what does it cost?* Every number below comes from `covcontact run` on a deck of
`input/verification/contact/` (including a frozen copy of the paper's example 6.1(a)) with one
parameter changed.

## How the errors are measured

**Reference-aware runs.** A deck may declare `reference` lines (see `input/README.md`): a value,
a table over time, or a named analytic solution (`hertz_sphere`, `hertz_cylinder`,
`cattaneo_mindlin_sphere`, `cattaneo_mindlin_cylinder`) with its parameters. `covcontact run`
samples every reference on each converged step and prints, after the run,

```
reference                                                measured    reference      error  max error
contact:hertz:force:z (hertz_sphere)                      15.1049      15.1723    -0.445%    +0.445%
contact:hertz:radius (hertz_sphere)                      0.962613       1.0102     -4.71%     +4.71%
contact:hertz:centre_pressure (hertz_sphere)              7.01439      7.06716    -0.747%    +0.747%
cost: 19.87 s wall time, 9 Newton iterations, 1 steps
```

and stores the same in the results file: `/verification` (attributes `wall_seconds`,
`newton_iterations`, `steps`) with one group `reference_K` per line (attributes `quantity`,
`kind` = value | table | analytic, `analytic`, `parameters`, `location` (deck file:line),
`time`, `measured`, `reference`, `error` = measured - reference and `relative_error` of the
last sample, `max_error`, `max_relative_error` over all samples; datasets `time`, `measured`,
`reference` per sampled step). The code is `src/verification/`.

**Analytic solutions** (K. L. Johnson, *Contact Mechanics*, 1985): Hertz sphere
a = (3PR/4E\\*)^(1/3), p0 = 3P/(2 pi a^2), delta = a^2/R; Hertz cylinder b = (4P'R/(pi E\\*))^(1/2),
p0 = 2P'/(pi b); Cattaneo-Mindlin stick radius c = a (1 - Q/(mu P))^(1/3) (sphere) and
c = b (1 - Q/(mu P))^(1/2) (cylinder), tangential approach 3 mu P/(16 a) ((2 - nu1)/G1 +
(2 - nu2)/G2)(1 - (1 - Q/(mu P))^(2/3)). Conventions: the load acts along z, cylinder axes lie
along y, body 1 (the indenter, parameters `E1`, `nu1`, rigid when omitted) is above body 2
(`E`, `nu`). Cattaneo-Mindlin needs Dundurs' beta = 0 (elastically similar bodies) and refuses
other pairs. Radii, widths and pressures are compared at the *measured* load (|F| of the pair
divided by the modelled `fraction`, and by `length` in plane strain), so they test the contact
discretization, not the body's stiffness.

**P(delta) of finite bodies.** Hertz' delta is the approach of points far away in two
half-spaces; a model has a fixed bottom at a finite depth. The reference therefore uses the
approach of two *probe* nodes on the load axis (`probe1_z`, `probe2_z`: the indenter's top and
the block's bottom, or the rigid surface's translation for STAS) and subtracts from Hertz'
approach the half-space displacement of those points, integrated from Boussinesq's point load
over the Hertz pressure (Cerruti's over the Cattaneo-Mindlin traction for Q(delta_t)). The load
whose corrected approach equals the measured one is the reference. What remains is the
difference between the finite block and a half-space (see the domain-size sweep).

**Measures read from the contact points** (model-free, the same for every kind):
contact radius = radius of the disk with the area of the points in contact
(sqrt(A / (pi fraction))), stick radius = the same for the points in state *stick* (so c is read
from the stick/slip state of the integration points: the stick zone's area), half-widths =
area / (2 length fraction); `centre_pressure` = -N at the contact point nearest the load axis,
`peak_pressure` = the largest -N of all points; patch tests: `pressure_deviation` = max
|p_i - mean| / mean over the points, `nodal_pressure_deviation` = the same for the slave nodes'
contact force divided by their tributary area.

**Run time.** The machine is shared by several jobs on 2 cores, so wall time mostly measures
the other jobs. Each run here uses `--threads 1` under `nice`; the plots use its CPU time (user +
system), which is the wall time on a free core. Both are in the tables.

**Penalty.** Penalties are given as alpha = eps_N h / E (h: element size in the contact zone):
alpha = 30 is the default of the Hertz and Cattaneo-Mindlin decks, and eps_T = eps_N.

**What was left out.** The machine is shared (2 cores, load 10-20 while these ran), so levels that
cost minutes of CPU per run were not run: the rigid sphere at m = 11, the elastic sphere with NTS
at m >= 6, the Cattaneo-Mindlin sphere at m = 5 (so it has 3 mesh levels, not 4) and example 6.1
at 160 x 40. CPU times under such load scatter by about 30% between identical runs."""

CASE_TITLES = {
    "hertz_rigid_sphere": "Hertz: rigid sphere on an elastic block (STAS)",
    "hertz_elastic_sphere": "Hertz: elastic sphere on an elastic block (STS)",
    "hertz_elastic_sphere_nts": "Hertz: elastic sphere on an elastic block (NTS)",
    "hertz_elastic_sphere_segments": "Hertz: elastic sphere on an elastic block (STS, integration=segments)",
    "hertz_elastic_sphere_smooth": "Hertz: elastic sphere on an elastic block (STS, surface=smooth)",
    "hertz_elastic_sphere_smooth_segments":
        "Hertz: elastic sphere on an elastic block (STS, surface=smooth integration=segments)",
    "hertz_elastic_sphere_augmented": "Hertz: elastic sphere on an elastic block (STS, enforcement=augmented)",
    "hertz_cylinder": "Hertz: rigid cylinder in plane strain (STAS)",
    "cattaneo_mindlin_sphere": "Cattaneo-Mindlin: elastic sphere on an elastic block (STS)",
    "cattaneo_mindlin_cylinder": "Cattaneo-Mindlin: elastic cylinder in plane strain (STS)",
    "patch_sts_matching": "Patch test: matching meshes (STS)",
    "patch_sts": "Patch test: non-matching meshes (STS)",
    "patch_nts": "Patch test: non-matching meshes (NTS)",
    "patch_sts_segments": "Patch test: non-matching meshes (STS, integration=segments)",
    "example_6_1": "Paper example 6.1(a): sliding block (STS)",
}

ELASTIC_SPHERE_NOTE = """Elastic sphere R = 100 (its lower cap, 32 high) on a block of the same
material, quarter model, STS with the sphere as master (deck mesh m = 8, alpha = 30). **What limits
the accuracy: the mesh of the two bodies, and the cost.** Two bodies of hex8 make P(delta) too
soft on coarse meshes: -4.6%, -3.0%, -2.0% at m = 3, 4, 6 (order ~h^1.1). The contact radius is
within 0.15-0.43 h at every level and the centre pressure within 0.3% at m = 6, but the largest
point pressure is +20% to +53%: single slave points near the contact edge, where the faceted
sphere's master segments meet the block's slave segments at an angle, carry pressure spikes
(STS point tractions oscillate on non-matching pairs, like the non-matching patch test). The
cost grows steeply: 4 s at m = 3, 46 s at m = 6, 102 s at the deck's m = 8, where P(delta) is
-1.5% (target met), a 0.25 h, the centre pressure -0.25% and the largest point pressure still
+20%. NTS on the same pair (block nodes as slaves) has no such spikes (peak = centre pressure:
+1.2%, -0.7% at m = 3, 4) but a cruder contact radius (+33%, +7.8%).
**Targets on the finest mesh under 60 s (m = 6, 46 s):** contact radius met (0.15 h), centre
pressure met (+0.23%), **P(delta) missed (-2.04%, target 2%)**, **peak pressure missed (+22%,
target 3%)** (test `VerificationHertz.ElasticSphereStsRadiusAndCentrePressure` asserts the two
that are met and records the two misses). A soft penalty trades the spike for force: at m = 4,
alpha = 3 gives the peak pressure within -1.6% but P(delta) -5.8%; raising the penalty moves
P(delta) only to its mesh limit (-5.8%, -3.8%, -3.0%, -2.6% at alpha = 3, 10, 30, 100 on m = 4)
while the spike grows (+11%, +26%, +40% at alpha = 10, 30, 100)."""

CATTANEO_MINDLIN_SPHERE_NOTE = """Elastic sphere R = 100 on a block of the same material (Dundurs
beta = 0), half model 16 a wide and deep, STS, mu = 0.3: normal load in one step, then 5 steps of
tangential displacement to Q/(mu P) ~ 0.6, so c/a ~ 0.74. The stick radius is read from the
stick/slip state of the slave Gauss points: c = sqrt(2 A_stick / pi). **What limits the accuracy:
the mesh, and the cost of the half model.** With a/h = 1.3-2.7 the stick disk holds only a few
Gauss points, so c jumps: -4.5% at m = 2 (0.04 h, by luck), -24% at m = 3 (0.35 h), -12% at
m = 4 (0.24 h): always within one element but not monotonic. The tangential compliance (Q at the
measured tangential approach) is +6.4%, -4.9%, -3.4%; P(delta) stays at -3.8% to -4.9% because
the block is only 16 a deep (compare the rigid sphere: -1.1% at 16 a) and coarse. The deck's mesh
(m = 4) takes 49 s of one core; m = 5 (about 2.5 minutes) was not run on the shared machine.
Load steps and penalty hardly matter at m = 3: 2 tangential steps give the same c (-23.9%) and Q
(-4.9%) as 5; alpha = 10 gives c -23.2%, Q -4.4% and P(delta) -5.9% (-4.9% at alpha = 30).
Target met: c within 0.24 h at m = 4 (deck, 49 s) and 0.18 < h(4) at m = 3 (30 s, test
`VerificationCattaneoMindlin.SphereStickRadiusWithinOneElementOfTheDeckMesh`)."""

EXAMPLE_NOTE = """Example 6.1(a) of the paper (block 20 x 5 on a supported base, STS, mu = 0.3, one
pressing step and 100 sliding steps; frozen copy `input/verification/contact/sliding_block_6_1a.deck`).
There is no analytic solution; each sweep is compared with its finest run (mesh: 80 x 20 block
elements; steps: 200 sliding steps; penalty: 10 x 2.1e6). Error = max over the sliding phase of
|F(t) - F_ref(t)| / max |F_ref| for the tangential (F_x) and normal (F_y) contact force. **What
limits the accuracy: the mesh.** 1.7% at 10 x 3, 0.68% at 20 x 5, 0.17% at the deck's 40 x 10,
0.06% at 60 x 15 (order ~h^1.8; against a reference only twice finer, so the finer levels'
errors are underestimated by up to a third). The step count does not matter from 50 sliding
steps on (1e-9) and costs 0.007% at 25: the sliding is steady.
The penalty matters as much as the mesh: 2.1% at eps_N = 2.1e5 and 0.19% at the paper's 2.1e6
against 2.1e7 (~1/eps_N), at the same Newton count (375-387), so a tenfold penalty is free here.
The paper's settings (40 x 10, 100 steps, 2.1e6: 7 s) are accurate to about 0.3% in the
contact force history."""

CASE_NOTES = {
    "hertz_rigid_sphere": """Rigid sphere R = 100 pressed 0.01 into a quarter block 32 a wide and
deep (a = 1; deck mesh m = 8, h = a/5.3, alpha = 30). **What limits the accuracy: the penalty
and the domain for P(delta), the Gauss-point spacing for a.** The force error falls like 1/alpha
(P -11.5%, -4.0%, -1.0%, -0.13% at alpha = 1, 3, 10, 30) until the mesh error (~0.1-0.5%) is
reached; alpha = 100 gains nothing and puts a +9% pressure spike on one edge point. The finite
block leaves -3.2%, -1.1%, -0.13% in P(delta) at L = 8, 16, 32 a after the half-space correction
of the probe. The contact radius is read from the area of the contact points and moves by
fractions of a Gauss-point spacing: within 0.09-0.31 h at every level. The largest point pressure
equals the centre pressure from m = 6 on (-0.5%); at m = 3, 4 (a/h < 3) a single point near the
axis carries +14-18%. Targets met on the deck's mesh (11 s): P(delta) -0.45%, a 0.25 h, peak
pressure -0.75% (test `VerificationHertz.RigidSphereStasOnTheDeckMesh`); m = 6 does as well in
half the time (-0.14%, 0.14 h, -0.46%).""",
    "hertz_elastic_sphere": ELASTIC_SPHERE_NOTE,
    "hertz_elastic_sphere_nts": """The elastic-sphere deck with `contact nts` (block nodes as
slaves on the sphere's segments), two mesh levels only (m >= 6 was not run): P(delta) -6.1%,
-2.9% at m = 3, 4 (like STS), no pressure spikes (peak = centre: +1.2%, -0.7%), but the radius,
read from the nodes in contact, is +33% and +7.8% (0.64 h, 0.20 h): one node ring more or less.""",
    "cattaneo_mindlin_sphere": CATTANEO_MINDLIN_SPHERE_NOTE,
    "example_6_1": EXAMPLE_NOTE,
    "hertz_cylinder": """Rigid cylinder R = 100 on a plane-strain slab one element thick (deck mesh
m = 16). **What limits the accuracy: the mesh for b, the penalty for p0.** The half-width is read
from the area of the contact points, so it moves in jumps of about one Gauss-point spacing (h/2 at
2 points per direction): -4.3% (0.45 h) up to m = 16, +0.5% from m = 32. It is within one element
at every level. The pressure is within 0.5% from m = 8 on and is then set by the penalty: p0 is
-3.4% at alpha = 1, -0.6% at alpha = 10, -0.3% at alpha = 300; above alpha = 30 Newton needs
4-50 times more iterations (56, 184, 612) and cut-backs for less than 0.1% gain. Target met on the
deck's mesh (0.9 s): p0 -0.41%, b within 0.45 h (test `VerificationHertz.RigidCylinderStasOnTheDeckMesh`).""",
    "cattaneo_mindlin_cylinder": """Elastic cylinder R = 100 on an elastic slab of the same
material in plane strain (Dundurs beta = 0), STS, mu = 0.3: normal load in one step, then 10
steps of tangential displacement to Q/(mu P) ~ 0.6. **What limits the accuracy: the mesh.** The stick
half-width is the area of the points in state stick, so it is quantized like b: -40% (0.68 h) at
m = 4, -11.5% (0.39 h) at m = 8, -7.8% (0.53 h) at m = 16, -2.3% (0.31 h) at m = 32, always within
one element (order ~h^1.3). The number of tangential load steps changes nothing (2 to 40 steps
give identical errors: the loading is monotonic and Coulomb's law is integrated exactly by the
return map), only the cost (32 to 156 Newton iterations). A soft penalty (alpha = 3) happens to
give c within 0.2% because the penalty compliance widens the stick zone, but it costs 3% in b;
alpha = 100 adds cut-backs. The deck's mesh (m = 16) takes 17 s of one core; m = 32 takes 141 s.
Target met: c within 0.53 h at m = 16, and the CTest case runs m = 8 (6 s, 0.073 < h(16) = 0.094).""",
    "patch_sts_matching": """Two blocks, matching meshes, uniform pressure (the contact
patch test). **Exact:** the point and nodal pressure deviations are at round-off (1e-10 to
9e-10) at every mesh level and penalty, 6 orders below the target 1e-3 (test
`VerificationPatchTest.StsOnMatchingMeshesIsUniform`). The total force differs from the imposed
displacement's force only by the penalty compliance in series with the blocks (1.5e-6 at
eps_N = 1e6), which falls like 1/eps_N: see the penalty-convergence plot.""",
    "patch_sts": """Non-matching meshes (n and n+1 elements across the interface).
**What limits the accuracy: the mesh and the penalty, in opposite directions.** The slave
nodes' force per tributary area is uniform to 0.5-1.3% at every level; the pressure at single
Gauss points oscillates (0.38 at n = 2, 0.074 at n = 16, order ~h^0.8). A larger penalty makes
the nodal forces more uniform (0.006 at eps_N = 1e3, 9e-5 at 1e8) but the point tractions less
(0.012 to 0.42): the stiff penalty enforces the non-matching geometry point by point. 4 Gauss
points per direction bring the point deviation to 0.07 at n = 4. The total force is exact to
5e-5.""",
    "patch_nts": """Non-matching meshes, node-to-segment. **What limits the accuracy: the
mesh.** NTS does not pass the patch test: the nodal pressure deviates by 19% (n = 2), 15%, 9.6%,
5.4% (n = 16), order ~h^0.6, independent of the penalty above eps_N = 1e5. The total force error
falls fast with the mesh (1% at n = 2, 0.002% at n = 16). Use STS where pressure distributions
matter.""",
}

RECOMMENDATIONS = """## Recommended settings

Read from the sweeps above (CPU times on one core; the wall time on the shared machine was 5-15
times longer).

| choice | recommendation | why (numbers from the tables) |
|---|---|---|
| penalty | alpha = eps_N h / E = 10-30, eps_T = eps_N | force and penetration errors fall like 1/alpha (slopes -1.0, -0.95 on the Hertz sphere; -1 on the patch test); alpha = 30 leaves 0.1-0.5% in P(delta) and p0; alpha = 100 buys < 0.3% but costs 30-400% more Newton iterations (cylinder: 12 -> 56, with cut-backs) and edge pressure spikes |
| mesh, normal contact | a/h >= 4 (contact radius over >= 4 elements) | rigid sphere at a/h = 4 (m = 6, 6 s): P(delta) -0.14%, p0 -0.46%, a 0.14 h; cylinder at b/h = 5 (m = 8, 0.4 s): p0 -0.5% |
| mesh, stick zones | a/h >= 10 for c within 10% | the stick radius is read from the stick points' area and is quantized by the Gauss-point spacing: cylinder c -7.8% at b/h = 11, -2.3% at 21; the sphere's c at a/h <= 2.7 is within one element but not better than 12% |
| load steps | as few as converge: 1 step for normal load, 2-5 for monotonic tangential load, 50 sliding steps (5e-4 each) in example 6.1 | no step-size error in Hertz/Cattaneo-Mindlin (2 and 40 steps give the same c); example 6.1: 25 steps 0.007%, 50 steps 1e-9 |
| domain | >= 32 a in width and depth for P(delta) | the half-space correction leaves -3.2%, -1.1%, -0.13% at 8, 16, 32 a |
| contact kind | STAS for rigid indenters, STS for deformable pairs, not NTS where pressures matter | STS passes the patch test on matching meshes to 1e-9 and has nodal pressures uniform to ~1% on non-matching ones; NTS deviates 5-19%; elastic-on-elastic STS costs ~8 times the rigid STAS run at the same h (46 s vs 6 s at m = 6) |

## Targets of issue 6 on meshes that run in under 60 s

| target | case (mesh, CPU) | measured | status |
|---|---|---|---|
| Hertz peak pressure within 3% | rigid sphere STAS (m = 8, 11 s) | -0.75% | met |
| | rigid cylinder STAS (m = 16, 0.9 s) | -0.41% | met |
| | elastic sphere STS (m = 6, 46 s) | +22% (largest point pressure; centre +0.23%) | **missed** (+20% at m = 8 too: STS edge spikes, not resolution) |
| contact radius within one element | rigid sphere STAS (m = 8) | 0.25 h | met |
| | rigid cylinder STAS (m = 16) | 0.45 h | met |
| | elastic sphere STS (m = 6) | 0.15 h | met |
| P(delta) within 2% | rigid sphere STAS (m = 8) | -0.45% | met |
| | elastic sphere STS (m = 6) | -2.04% | **missed** (by 0.04%; converging like h^1.1: -1.51% on the deck's m = 8, which takes 102 s) |
| Cattaneo-Mindlin stick radius within one element | sphere STS (m = 4, 49 s; m = 3, 30 s) | 0.24 h; 0.35 h | met |
| | cylinder STS (m = 16, 17 s; m = 8, 6 s) | 0.53 h; 0.39 h | met |
| STS patch test on matching meshes within 1e-3 | 4 x 4 (0.2 s) | 2e-10 | met |
| penalty slope 1/eps_N | patch test, eps_N = 1e5 -> 1e6 | slopes 1.00 (penetration), 0.996 (force) | met (test `VerificationPenalty.PatchTestErrorsFallLikeOneOverPenalty`) |

The CTest cases (label `verification`) assert every *met* target on the mesh named in the table
(or on a coarser mesh against the deck mesh's element size); the two misses are recorded in the
test output and here, not asserted with a wider tolerance."""
