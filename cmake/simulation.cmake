# Scene and sensor simulation (pda_simulate) and bag evaluation tools; see issue "Offline".
