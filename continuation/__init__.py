"""Generic pseudo-arclength continuation of curves H(x) = 0, H: R^(n+1) -> R^n.

The engine follows a solution curve through folds in any coordinate, locates
events, folds and simple branch points exactly, switches branches and closes
loops, and follows folds and event points in a second parameter (:mod:`.codim2`)
(E. L. Allgower and K. Georg, *Introduction to Numerical Continuation Methods*, SIAM 2003;
H. B. Keller, 1977). It imports numpy and scipy only; :func:`certify` proves a traced curve
in ball arithmetic with python-flint (optional, imported when used).

Example
-------
>>> import numpy as np
>>> from continuation import Problem, Options, trace
>>> circle = Problem(lambda x: np.array([x[0]**2 + x[1]**2 - 1.0]),
...                  lambda x: np.array([[2 * x[0], 2 * x[1]]]))
>>> curve = trace(circle, [1.0, 0.0], options=Options(fold_coordinates=(0, 1)))
>>> curve.status.name
'CLOSED'
"""

from .branching import branch_tangents, locate_branch_point, switch_branch
from .certification import Certificate, CertifyOptions, certify
from .codim2 import Codim2Curve, Codim2Kind, Codim2Point, follow_event, follow_fold
from .errors import CallbackError, CallbackShapeError, ContinuationError
from .events import Event, box_events
from .family import Family
from .options import Options
from .problem import Problem, check_jacobian, finite_difference_jacobian
from .result import Curve, SpecialKind, SpecialPoint, Status
from .tracker import trace

__all__ = [
    "CallbackError",
    "Certificate",
    "CertifyOptions",
    "CallbackShapeError",
    "Codim2Curve",
    "Codim2Kind",
    "Codim2Point",
    "ContinuationError",
    "Curve",
    "Event",
    "Family",
    "Options",
    "Problem",
    "SpecialKind",
    "SpecialPoint",
    "Status",
    "box_events",
    "branch_tangents",
    "certify",
    "check_jacobian",
    "finite_difference_jacobian",
    "follow_event",
    "follow_fold",
    "locate_branch_point",
    "switch_branch",
    "trace",
]

import logging as _logging

# a library logs, the application decides where it goes
_logging.getLogger(__name__).addHandler(_logging.NullHandler())
