"""Message decoders per family: one decoded message in, one sample (ego, objects, plan) out.

- ``ros_ego``, ``ros_objects``, ``ros_plan``: ROS 1 / ROS 2 messages (rosbags dataclasses);
- ``foxglove``: Foxglove protobuf schemas in MCAP (``foxglove.Odometry``, ``SceneUpdate``, ...);
- ``mcap_json``: our JSON schemas in MCAP (``workbench.EgoState``, ``ObjectList``, ``Plan``).

Which type goes to which decoder: ``loaders.message_logs.registry.FAMILIES``.
"""
