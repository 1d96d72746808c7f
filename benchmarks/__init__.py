"""Benchmarks of the continuation engine and the boundary tracer (``python benchmarks/run.py``)."""
