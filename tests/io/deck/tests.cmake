# Deck reader tests (paths relative to tests/io).
xpl_add_test_executable(
  xpl_tests_io_deck deck/test_deck_reader.cpp deck/test_deck_features.cpp deck/test_deck_errors.cpp
  deck/test_deck_numbers.cpp deck/test_deck_large.cpp deck/test_deck_shells.cpp
  deck/test_deck_shell_errors.cpp deck/test_deck_pressure_errors.cpp deck/test_deck_contact.cpp
  deck/test_deck_contact_errors.cpp deck/test_deck_contact_lines.cpp
  deck/test_deck_node_surfaces.cpp deck/test_deck_calculix.cpp deck/test_deck_rigid_errors.cpp
  deck/test_deck_clearance.cpp deck/test_deck_clearance_errors.cpp deck/test_deck_initialization.cpp deck/test_deck_keywords.cpp
  deck/test_model_checks.cpp deck/test_deck_plastic.cpp deck/test_deck_plastic_errors.cpp
  deck/test_deck_initial_rotation.cpp deck/test_deck_dynamic.cpp deck/test_deck_assembly.cpp
  deck/test_deck_mesh_export.cpp deck/test_deck_refusals.cpp)
target_link_libraries(xpl_tests_io_deck PRIVATE xpl::io_deck)
