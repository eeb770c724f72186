# The reference docs against the code (docs/ vs cfg/*.cfg, src/ros, launch/*.launch; relative
# links; the README's size). Reads the files from the repository at run time: no rebuild is
# needed to re-check an edited page. Included from test/CMakeLists.txt.
catkin_add_gtest(docs_reference_test docs_reference_test.cpp docs_check_test.cpp
                 docs_check/markdown.cpp docs_check/reference_docs.cpp)
target_compile_options(docs_reference_test PRIVATE ${PDA_WARNINGS})
target_include_directories(docs_reference_test PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
target_compile_definitions(docs_reference_test PRIVATE PDA_REPO_DIR="${PDA_REPO_DIR}")
target_link_libraries(docs_reference_test gtest_main)
