# gtests for the simulation. Included from test/CMakeLists.txt.
# The scene and the sensors (ray casting, Kinect 2 and VLP-16 geometry and noise).
catkin_add_gtest(sensor_simulation_test sensor_simulation_test.cpp)
target_compile_options(sensor_simulation_test PRIVATE ${PDA_WARNINGS})
target_link_libraries(sensor_simulation_test pda_registration_simulation gtest_main)

# The simulated cases (a small office, the lidar car park) and one perturbed alignment, shared
# by the simulation and registration tests.
add_library(pda_simulated_cases STATIC test_support/simulated_cases.cpp
  test_support/traced_alignment.cpp)
target_compile_options(pda_simulated_cases PRIVATE ${PDA_WARNINGS})
target_link_libraries(pda_simulated_cases pda_test_support pda_registration_simulation gtest)

# The whole simulation: distortion, determinism, PDA on the simulated maps.
catkin_add_gtest(map_simulation_test map_simulation_test.cpp)
target_compile_options(map_simulation_test PRIVATE ${PDA_WARNINGS})
target_link_libraries(map_simulation_test pda_simulated_cases gtest_main)

# What the simulation writes: its bag and the pda_simulate tool (run as a user runs it).
catkin_add_gtest(map_simulation_files_test map_simulation_files_test.cpp)
target_compile_options(map_simulation_files_test PRIVATE ${PDA_WARNINGS})
# The bag tests read the bag back with rosbag::View.
target_include_directories(map_simulation_files_test SYSTEM PRIVATE ${catkin_INCLUDE_DIRS})
target_link_libraries(map_simulation_files_test
  pda_simulated_cases gtest_main ${catkin_LIBRARIES})
target_compile_definitions(map_simulation_files_test PRIVATE
  PDA_SIMULATE_BINARY="$<TARGET_FILE:pda_simulate>")
add_dependencies(map_simulation_files_test pda_simulate)

# The pose covariance against Monte Carlo and the simulated office's exact ground truth.
catkin_add_gtest(pose_covariance_test pose_covariance_test.cpp)
target_compile_options(pose_covariance_test PRIVATE ${PDA_WARNINGS})
target_link_libraries(pose_covariance_test
  pda_test_support pda_registration_simulation gtest_main)

# Registration on the simulated outdoor and same-sensor lattice cases (no ROS needed).
catkin_add_gtest(lattice_registration_test lattice_registration_test.cpp)
target_compile_options(lattice_registration_test PRIVATE ${PDA_WARNINGS})
target_link_libraries(lattice_registration_test pda_simulated_cases gtest_main)

# Scan lines are not surfaces: the normal map on noise-thickened rings, the scan-line scale, and
# the same-sensor VLP-16 office it kept one ring off.
catkin_add_gtest(scan_lines_test scan_lines_test.cpp)
target_compile_options(scan_lines_test PRIVATE ${PDA_WARNINGS})
target_link_libraries(scan_lines_test pda_simulated_cases gtest_main)

# The ground truth of a warped dense map: the best rigid fit of the warp over the overlap.
catkin_add_gtest(warp_rigid_fit_test warp_rigid_fit_test.cpp)
target_compile_options(warp_rigid_fit_test PRIVATE ${PDA_WARNINGS})
target_link_libraries(warp_rigid_fit_test
  pda_test_support pda_registration_simulation gtest_main)

# Reach and verdict of the defaults: the approach subset, the lattice from 10 deg, RGB-D fragments.
catkin_add_gtest(registration_reach_test registration_reach_test.cpp)
target_compile_options(registration_reach_test PRIVATE ${PDA_WARNINGS})
target_link_libraries(registration_reach_test pda_simulated_cases gtest_main)

# The least-squares polish over a warped overlap: when it applies, the warped fragment pair.
catkin_add_gtest(warp_polish_test warp_polish_test.cpp)
target_compile_options(warp_polish_test PRIVATE ${PDA_WARNINGS})
target_link_libraries(warp_polish_test pda_simulated_cases gtest_main)

# Where the noise model reads a point's target normal: the lookup, warped fragment pairs.
catkin_add_gtest(normal_lookup_test normal_lookup_test.cpp)
target_compile_options(normal_lookup_test PRIVATE ${PDA_WARNINGS})
target_link_libraries(normal_lookup_test pda_simulated_cases gtest_main)

# A second pose along the least certain direction: walls, and the car park on another day.
catkin_add_gtest(competing_shift_test competing_shift_test.cpp)
target_compile_options(competing_shift_test PRIVATE ${PDA_WARNINGS})
target_link_libraries(competing_shift_test pda_simulated_cases gtest_main)

# The second start as align() runs it: questioned at the first attempt's nu floor.
catkin_add_gtest(second_start_test second_start_test.cpp)
target_compile_options(second_start_test PRIVATE ${PDA_WARNINGS})
target_link_libraries(second_start_test pda_simulated_cases gtest_main)

# The turned start: the seed turned about the sensor, on the 3-m and 20-m VLP-16 scan pairs.
catkin_add_gtest(turned_start_test turned_start_test.cpp)
target_compile_options(turned_start_test PRIVATE ${PDA_WARNINGS})
target_link_libraries(turned_start_test pda_simulated_cases gtest_main)

# The near search where the usual answer is questionable: its radius, its verdict, RGB-D fragments
# sharing a third of the scene.
catkin_add_gtest(near_search_test near_search_test.cpp)
target_compile_options(near_search_test PRIVATE ${PDA_WARNINGS})
target_link_libraries(near_search_test pda_simulated_cases gtest_main)
