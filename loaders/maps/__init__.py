"""Lane maps: one lane-graph model and readers for Lanelet2, CommonRoad and OpenDRIVE."""
