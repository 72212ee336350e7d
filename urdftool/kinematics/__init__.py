"""Kinematics: the tree, forward kinematics and Denavit-Hartenberg tables."""
