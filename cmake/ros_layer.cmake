# The thin ROS layer: message conversions, markers, settings and the nodelet.
include_directories(SYSTEM ${catkin_INCLUDE_DIRS})

# PointCloud2 <-> point list, shared by the nodelet, the bag tools and the simulator's bag writer.
add_library(pda_registration_conversions src/ros/point_cloud_conversion.cpp)
target_compile_options(pda_registration_conversions PRIVATE ${PDA_WARNINGS})
target_link_libraries(pda_registration_conversions pda_registration_core ${catkin_LIBRARIES})

add_library(pda_registration_ros
  src/ros/alignment_job.cpp
  src/ros/alignment_output.cpp
  src/ros/alignment_publisher.cpp
  src/ros/alignment_status.cpp
  src/ros/association_markers.cpp
  src/ros/dense_map_keeper.cpp
  src/ros/edge_broadcaster.cpp
  src/ros/idle_cores.cpp
  src/ros/initial_transform.cpp
  src/ros/live_parameters.cpp
  src/ros/map_alignment_intake.cpp
  src/ros/map_alignment_nodelet.cpp
  src/ros/node_settings.cpp
  src/ros/rate_budget.cpp
  src/ros/seed_lookup.cpp
  src/ros/tf_edge.cpp
)
target_compile_options(pda_registration_ros PRIVATE ${PDA_WARNINGS})
target_link_libraries(pda_registration_ros pda_registration_conversions ${catkin_LIBRARIES})
add_dependencies(pda_registration_ros ${PROJECT_NAME}_gencfg ${catkin_EXPORTED_TARGETS})

install(TARGETS pda_registration_conversions pda_registration_ros
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
install(FILES nodelet_plugins.xml DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})
install(DIRECTORY launch cfg rviz DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})

# End-to-end latency of the running nodelet (scripts/measure_latency).
add_executable(pda_latency_probe src/tools/pda_latency_probe.cpp)
target_compile_options(pda_latency_probe PRIVATE ${PDA_WARNINGS})
target_link_libraries(pda_latency_probe pda_registration_ros pda_registration_tools ${catkin_LIBRARIES})
install(TARGETS pda_latency_probe RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

# Latency while the dense map grows like a SLAM map (scripts/measure_latency --growing).
add_executable(pda_growing_probe src/tools/pda_growing_probe.cpp)
target_compile_options(pda_growing_probe PRIVATE ${PDA_WARNINGS})
target_link_libraries(pda_growing_probe pda_registration_ros pda_registration_tools ${catkin_LIBRARIES})
install(TARGETS pda_growing_probe RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
