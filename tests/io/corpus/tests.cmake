# The corpus of decks as users have them (tests/data/decks; issue 34, SPEC I5): a CAE-style
# part/assembly deck against the same model written flat, gmsh block and plate, a meshio export,
# CalculiX-style decks. Each case reads its deck (counts, sets, coordinates) and runs it; none
# needs gmsh or meshio installed (the exports are committed as written). Two to four runs of
# at most 54 nodes per case: seconds.
foreach(case cae_assembly gmsh_block gmsh_plate meshio_block calculix_massless
             calculix_clearance calculix_refused)
  add_test(NAME io_corpus_${case}
           COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/corpus/check_corpus.py
                   $<TARGET_FILE:xpl> ${PROJECT_SOURCE_DIR}/tests/data/decks
                   ${CMAKE_CURRENT_BINARY_DIR}/corpus/${case} ${case})
  set_tests_properties(io_corpus_${case} PROPERTIES LABELS "io;corpus" TIMEOUT 120
                                                    ENVIRONMENT OMP_WAIT_POLICY=PASSIVE)
endforeach()
