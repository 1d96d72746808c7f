"""The friction coefficients audited by default, in a module that imports nothing.

``groove audit --help`` names them; it should not wait for numpy and the solver.
"""

__all__ = ["DEFAULT_KS"]

#: Friction coefficients audited by default: both sides of k = sqrt 2 and of k = 1, and the
#: k = 1 and k = 10 of the paper's Fig. 2.
DEFAULT_KS = (0.3, 1.0, 1.2, 1.4, 1.5, 2.0, 10.0, 100.0)
