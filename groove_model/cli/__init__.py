"""The ``groove`` command line: one module per command, the parser and entry point in ``main``."""

from .main import build_parser, main

__all__ = ["build_parser", "main"]
