# Example 6.3 (semi-cylinder on a rigid parabolic cylinder, STAS): the press and 3 spiral steps
# with the tangent without curvature parts and with the main part only (Table 5's two cases).
# References: the runs' results shrunk by shrink_reference.py (compare reads only iteration
# counts, set reactions and contact total forces), regenerate with
#   covcontact run decks/NAME.deck --output NAME.h5 && shrink_reference.py NAME.h5 reference/NAME.h5
foreach(tangent no_curvature main)
  cc_add_paper_regression(NAME example_6_3_${tangent}
    DECK ${CMAKE_CURRENT_SOURCE_DIR}/decks/semi_cylinder_6_3_${tangent}_short.deck
    REFERENCE semi_cylinder_6_3_${tangent}_short.h5
    ARGS --threads 1)
endforeach()
