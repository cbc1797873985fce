"""The package version (pyproject.toml's), for every module that names it."""

__version__ = "0.1.0"
