# pda_bag_eval: offline evaluation of parameter sets on recorded bags.
