# The thin ROS layer: conversions, markers, the nodelet. Filled in with the nodelet.
