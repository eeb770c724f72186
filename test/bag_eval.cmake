# Tests of pda_bag_eval; included from test/CMakeLists.txt. The binary runs as a user runs it, on
# bags the test simulates and writes itself.
catkin_add_gtest(bag_eval_test bag_eval_test.cpp)
target_compile_options(bag_eval_test PRIVATE ${PDA_WARNINGS})
target_link_libraries(bag_eval_test
  pda_test_support pda_registration_simulation pda_registration_bag_eval gtest_main
  ${catkin_LIBRARIES})
target_compile_definitions(bag_eval_test PRIVATE PDA_BAG_EVAL_BINARY="$<TARGET_FILE:pda_bag_eval>")
add_dependencies(bag_eval_test pda_bag_eval)

# The parameter grid and the ranking of the sets, tested directly (no bag, no binary).
catkin_add_gtest(bag_eval_grid_ranking_test bag_eval_grid_ranking_test.cpp)
target_compile_options(bag_eval_grid_ranking_test PRIVATE ${PDA_WARNINGS})
target_link_libraries(bag_eval_grid_ranking_test
  pda_test_support pda_registration_bag_eval gtest_main)
