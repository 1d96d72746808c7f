"""The exceptions of the engine; each failed run's exception carries its partial curve."""

from __future__ import annotations

from typing import Any

__all__ = ["CallbackError", "CallbackShapeError", "ContinuationError"]


class ContinuationError(RuntimeError):
    """A continuation run failed; ``curve`` holds the partial :class:`~continuation.Curve`.

    (Typed ``Any`` here: the result module imports this one, not the other way round.)
    """

    def __init__(self, message: str, curve: Any = None) -> None:
        super().__init__(message)
        self.curve = curve


class CallbackError(ContinuationError):
    """A residual, Jacobian or event function raised an exception.

    ``curve`` holds the points traced before (status ``CALLBACK_FAILED``); the original
    exception is the ``__cause__``.
    """


class CallbackShapeError(ContinuationError, ValueError):
    """A residual, Jacobian or event function returned an array of the wrong shape, or
    values that are not real (complex numbers, objects).

    The message names the function, what was found and what was expected; ``curve``
    holds the points traced before (status ``CALLBACK_FAILED``).
    """
