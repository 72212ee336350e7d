"""One module per command; each has ``register(app)``. Shared option parsing lives in _common."""
