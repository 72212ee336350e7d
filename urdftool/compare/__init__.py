"""Comparing two robot descriptions: what changed (structure) and what it does (effect)."""
