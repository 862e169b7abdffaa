"""Not code: this marker makes the shipped material files the package
``flexlink.materials.data`` once installed (pyproject.toml maps it here), so that wheels and
editable installs both find them with importlib.resources."""
