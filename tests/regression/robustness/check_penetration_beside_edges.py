#!/usr/bin/python3
"""The penetration watch counts points under the master, not beside its free edges (issue 14).

NTS on the ironing die exactly as wide as the slab (ironing_nts_mu03_equal.deck, edge=fade):
the slab's side nodes, bulged out by the press, lie 0.03-0.05 beyond the die's side edges, in
the band where edge=fade lets the force fade out. Their gap is measured to the extension of the
die's edge facets, not into the die, and grows to a third of the slab's element depth by
t = 0.33, while the nodes under the die stay below a tenth of it. The run used to count them,
end with "the penetration reached ...: raise eps_n and eps_t", and store their gap as its
deepest penetration (restart data).

33 steps (t = 0.33). Independent reference, from the results file alone: at every converged
step, the closed points whose slave node lies within the die's bottom face across the slab
(y between the die_bottom nodes' smallest and largest y, widened by the free-edge tolerance of
1 % of a half segment, 0.0025) are under the die, the others beside it. Points within 5e-4 of
that border are left out: the die's own deformation blurs the border by about that much; the
test checks that none of them is deeper than the deepest under the die. Checked:
  - the case still shows what it tests: beside the die the deepest gap exceeds a quarter of the
    element depth, under it the deepest stays below;
  - the stored deepest penetration (restart table, last step) equals the deepest under the die
    to 1e-12 (the code before the fix stored the gap beside it);
  - the run ends without the penetration warning;
  - the results file's `edge_share` tells the two apart as the geometry does: 1 at every closed
    point under the die, below 1 at every closed point beside it (what a ParaView user filters
    on, docs/output-format.md).
About 15 s on one thread."""
import os
import sys

import h5py

import stress_script

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "support"))
from script_checks import check  # noqa: E402  (tests/support)

STEPS = 33
# The slab's element layer: 3 deep in 6 elements (meshes/ironing.geo); the warning's threshold
# is a quarter of it (contact_pair_diagnostics.cpp, kPenetrationWarningShare).
DEPTH = 0.5
WARNING_SHARE = 0.25
# The die's segments are 0.5 wide across the slab; the full force reaches 1 % of a half segment
# beyond a free edge (contact_point.hpp, kFreeEdgeTolerance).
EDGE_TOLERANCE = 0.01 * 0.25
BORDER = 5e-4  # a point this close to the widened edge is left out (docstring)
DEEPEST_COLUMN = 27  # contact_history: the pair's deepest penetration so far (output-format.md)

args = stress_script.parse_args()
deck = "ironing_nts_mu03_equal.deck"
r = stress_script.run_ironing_steps(args, deck, STEPS, ("contact nts", "edge=fade", "dieWidth=4"))
check(f"completed: {STEPS} steps" in r.stdout, "the run did not complete:\n" + r.stdout[-2000:])

path = os.path.join(args.scratch, f"ironing_nts_mu03_equal_{STEPS}.h5")
under = beside = on_border = 0.0
share_under_not_1 = share_beside_1 = beside_points = 0
with h5py.File(path, "r") as f:
    coordinates = f["mesh/coordinates"][()]
    die_bottom = f["mesh/node_sets/die_bottom/nodes"][()]
    steps = sorted(f["steps"])
    check(len(steps) == STEPS, f"{len(steps)} steps in the results file, expected {STEPS}")
    for name in steps:
        step = f["steps"][name]
        y_die = (coordinates + step["displacement"][()])[die_bottom, 1]
        low, high = y_die.min() - EDGE_TOLERANCE, y_die.max() + EDGE_TOLERANCE
        pair = step["contact/die"]
        closed = pair["state"][()] != 0
        y = pair["position"][()][:, 1]
        gap = pair["gap"][()]
        share = pair["edge_share"][()]
        inside = closed & (y >= low + BORDER) & (y <= high - BORDER)
        outside = closed & ((y < low - BORDER) | (y > high + BORDER))
        border = closed & ~inside & ~outside
        if inside.any():
            under = max(under, float(-gap[inside].min()))
        if outside.any():
            beside = max(beside, float(-gap[outside].min()))
        share_under_not_1 += int((share[inside] != 1).sum())
        share_beside_1 += int((share[outside] >= 1).sum())
        beside_points += int(outside.sum())
        if border.any():
            on_border = max(on_border, float(-gap[border].min()))
    stored = float(f["steps"][steps[-1]]["restart/contact_history/die"][0, DEEPEST_COLUMN])

print(f"deepest gap under the die {under:.4f}, beside it {beside:.4f}; stored {stored:.4f} "
      f"(element depth {DEPTH})")
check(beside > WARNING_SHARE * DEPTH,
      f"beside the die the deepest gap is {beside:.4f}, no more than a quarter of the element "
      "depth: the case no longer tests the watch")
check(under < WARNING_SHARE * DEPTH,
      f"under the die the deepest gap is {under:.4f}, above a quarter of the element depth")
check(on_border < under, f"a point at the die's edge, left out, has the deepest gap {on_border}")
check(abs(stored - under) <= 1e-12 * under,
      f"the stored deepest penetration is {stored!r}, the deepest under the die {under!r}")
check(share_under_not_1 == 0,
      f"{share_under_not_1} closed points under the die have an edge_share other than 1")
check(beside_points > 0 and share_beside_1 == 0,
      f"{share_beside_1} of {beside_points} closed points beside the die have edge_share 1")
check("the penetration reached" not in r.stdout + r.stderr,
      "the run warns of a penetration:\n" + r.stdout[-1500:])
print("ok")
