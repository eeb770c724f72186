# pda_bag_eval: offline evaluation of parameter sets on recorded bags (rosbag C++ API).
# The bag reader, the parameter grid and the report are a small library so the tests can use
# them directly; the tool's progress line lives there too.
add_library(pda_registration_bag_eval STATIC
  src/tools/bag_eval_row.cpp
  src/tools/bag_eval_summary.cpp
  src/tools/bag_maps.cpp
  src/tools/bag_parameter_grid.cpp
  src/tools/bag_transforms.cpp
  src/tools/progress_line.cpp
)
target_compile_options(pda_registration_bag_eval PRIVATE ${PDA_WARNINGS})
target_include_directories(pda_registration_bag_eval SYSTEM PUBLIC ${catkin_INCLUDE_DIRS})
target_link_libraries(pda_registration_bag_eval
  PUBLIC pda_registration_ros pda_registration_tools ${catkin_LIBRARIES})

add_executable(pda_bag_eval src/tools/pda_bag_eval.cpp)
target_compile_options(pda_bag_eval PRIVATE ${PDA_WARNINGS})
target_link_libraries(pda_bag_eval
  pda_registration_bag_eval pda_registration_ros pda_registration_tools ${catkin_LIBRARIES})

install(TARGETS pda_bag_eval RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
