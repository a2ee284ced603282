"""The interfaces layer: the command-line interface (one module per command)."""
