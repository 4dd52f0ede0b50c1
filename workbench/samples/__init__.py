"""Deterministic sample drives (scenarios, Lanelet2 maps and ROS/Foxglove logs) for demos and tests."""
