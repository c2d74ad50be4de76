# Paper example 6.2 (parabolic block on a parabolic base, NTS, 18-node solid-shells): shortened
# decks for the pressing (a), the equidistant motion (b) and full sliding (c) with the full and
# the main-part tangent; compared with the stored references (iterations per step exactly,
# set reactions and contact forces to 1e-8).
set(PAPER_6_2_DECKS ${CMAKE_CURRENT_SOURCE_DIR}/decks)
foreach(case 6_2a 6_2b 6_2c_full 6_2c_main)
  cc_add_paper_regression(NAME parabolic_block_${case}
    DECK ${PAPER_6_2_DECKS}/parabolic_block_${case}_short.deck
    REFERENCE parabolic_block_${case}_short.h5
    ARGS --threads 1 --quiet)
endforeach()
