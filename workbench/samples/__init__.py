"""Deterministic sample drives: scenarios, Lanelet2 maps, ROS and Foxglove logs."""
