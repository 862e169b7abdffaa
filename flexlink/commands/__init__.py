"""One module per CLI command; see ``flexlink/cli.py``."""
