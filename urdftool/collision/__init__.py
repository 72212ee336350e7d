"""Self-collision: FCL collision objects from ``<collision>``, checks at a pose, the MoveIt-style
collision matrix with convergence, and SRDF ``<disable_collisions>`` reading and writing.

Heavy libraries (numpy, fcl, trimesh) are imported by these modules, so import them only from
inside the command that needs them.
"""
