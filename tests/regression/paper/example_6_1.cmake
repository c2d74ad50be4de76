# Paper example 6.1 (sliding block, STS, bilinear): the first steps of 6.1(a) and of 6.1(b) with
# the full and the main-part tangent, compared with the stored references (iterations per step
# exactly, set reactions and contact total forces to 1e-8 relative). References: run the deck
# with the same arguments, then shrink_reference.py RUN.h5 reference/NAME.h5.
set(PAPER_6_1_DECKS ${CMAKE_CURRENT_SOURCE_DIR}/decks)
foreach(case 6_1a_short 6_1b_short_full 6_1b_short_main)
  cc_add_paper_regression(NAME sliding_block_${case}
    DECK ${PAPER_6_1_DECKS}/${case}.deck
    REFERENCE ${case}.h5
    ARGS --threads 1 --quiet)
endforeach()

# solve solver=umfpack|mumps|amg|gamg on 6.1(a): iterations per step as the reference (direct
# solvers exactly, iterative ones at most +1), the choice printed and logged (issue 13).
add_test(NAME paper.solver_choice_6_1a
  COMMAND ${SYSTEM_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/check_solver_choice.py
          --covcontact $<TARGET_FILE:covcontact> --deck ${PAPER_6_1_DECKS}/6_1a_short.deck
          --reference ${PAPER_REFERENCE_DIR}/6_1a_short.h5
          --scratch ${CMAKE_CURRENT_BINARY_DIR}/solver_choice)
set_tests_properties(paper.solver_choice_6_1a PROPERTIES LABELS paper TIMEOUT 600
  ENVIRONMENT "OMP_WAIT_POLICY=PASSIVE;OMP_NUM_THREADS=1")
