# Scene and sensor simulation (pda_simulate); see issue "Offline". The library is ROS-free except
# the bag writer, whose ROS types stay inside its .cpp (rosbag linked privately); it needs no
# PCL registration templates.
add_library(pda_registration_simulation
  src/simulation/drift_distortion.cpp
  src/simulation/kinect_simulator.cpp
  src/simulation/map_bag_writer.cpp
  src/simulation/map_simulation.cpp
  src/simulation/office_scene.cpp
  src/simulation/outdoor_scene.cpp
  src/simulation/scene.cpp
  src/simulation/sensor_paths.cpp
  src/simulation/velodyne_simulator.cpp
  src/simulation/warp_rigid_fit.cpp
)
target_compile_options(pda_registration_simulation PRIVATE ${PDA_WARNINGS})
target_include_directories(pda_registration_simulation SYSTEM PRIVATE ${catkin_INCLUDE_DIRS})
target_link_libraries(pda_registration_simulation
  PUBLIC pda_registration_core
  PRIVATE pda_registration_conversions ${catkin_LIBRARIES})

add_executable(pda_simulate src/tools/pda_simulate.cpp)
target_compile_options(pda_simulate PRIVATE ${PDA_WARNINGS})
target_link_libraries(pda_simulate pda_registration_simulation pda_registration_tools)

install(TARGETS pda_registration_simulation pda_simulate
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

# A real case folder as a bag in the same layout, for replay through the nodelet.
add_executable(pda_case_bag src/tools/pda_case_bag.cpp)
target_compile_options(pda_case_bag PRIVATE ${PDA_WARNINGS})
target_link_libraries(pda_case_bag pda_registration_simulation pda_registration_tools)
install(TARGETS pda_case_bag RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
