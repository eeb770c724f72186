# Tests of pda_bag_eval; included from test/CMakeLists.txt. The binary runs as a user runs it, on
# bags the test simulates and writes itself; the grid and the ranking are also tested directly.
catkin_add_gtest(bag_eval_test bag_eval_test.cpp)
target_compile_options(bag_eval_test PRIVATE ${PDA_WARNINGS})
target_link_libraries(bag_eval_test
  pda_test_support pda_registration_simulation pda_registration_bag_eval gtest_main
  ${catkin_LIBRARIES})
target_compile_definitions(bag_eval_test PRIVATE PDA_BAG_EVAL_BINARY="$<TARGET_FILE:pda_bag_eval>")
add_dependencies(bag_eval_test pda_bag_eval)
