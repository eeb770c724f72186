# Tests of pda_bag_eval; included from test/CMakeLists.txt.
