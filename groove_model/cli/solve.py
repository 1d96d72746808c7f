"""``groove solve``: the equilibrium at one point ``(gamma, delta)``, in words or as JSON."""

from __future__ import annotations

import json
import math
import sys

from .common import (
    EXIT_OK,
    UsageError,
    add_command,
    add_compliance_options,
    add_friction,
    compliance_from,
    one_friction,
    real,
)

__all__ = ["add_parser", "run"]

_EXAMPLES = """examples:
  groove solve --gamma 0.6 --delta 0.2 -k 1
  groove solve --gamma 40 --delta 10 -k 10 --deg --json
  groove solve --gamma 0.6 --delta 0.2 -k 1 --radius 0.01 --young 2e11 --poisson 0.3 --mass 0.033
  groove solve --gamma 0.6 --delta 0.2 -k 1 --compliance 0.8

angles are printed in full (17 significant digits at most), so a printed gamma or delta can be
given back to --gamma and --delta unchanged; --json writes every field, with k.
--poisson NU sets Mindlin's compliance 2 (1 - NU)/(2 - NU) and, with --radius, --young and
--mass, the Hertz contact of the SI results; --compliance RATIO overrides the compliance.
"""

#: The fields of ``--json``, in order (angles in radians, displacements per approach Z).
JSON_KEYS = ("k", "compliance", "regime", "rotation", "gamma", "delta", "theta_L", "theta_R",
             "beta_L", "beta_R", "upsilon", "T_over_N_L", "T_over_N_R", "N_L_over_N_R", "d_L",
             "d_R")


def add_parser(subparsers):
    """Register ``groove solve``; returns its parser."""
    p = add_command(
        subparsers, "solve",
        description="Print the equilibrium the paper predicts at one groove geometry: regime, "
                    "loading direction beta_L, beta_R, rolling upsilon, force ratios, slip, "
                    "rotation sense. Angles in radians unless --deg.",
        examples=_EXAMPLES)
    p.add_argument("--gamma", required=True,
                   type=real("gamma", "0 <= gamma <= pi/2 (90 with --deg)"),
                   help="half-sum of the wall angles, 0 <= gamma <= pi/2 (90 with --deg)")
    p.add_argument("--delta", required=True,
                   type=real("delta", "0 <= delta <= gamma"),
                   help="half-difference of the wall angles, 0 <= delta <= gamma")
    add_friction(p, help="friction coefficient (> 0)", traced=False, several=False)
    p.add_argument("--deg", action="store_true", help="--gamma and --delta are in degrees")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object (angles in radians)")
    dim = p.add_argument_group("dimensional results (need --radius, --young, --mass and --poisson)")
    positive = "finite and > 0"
    dim.add_argument("--radius", type=real("radius R", positive), help="ball radius R in m")
    dim.add_argument("--young", type=real("Young's modulus E", positive),
                     help="Young's modulus E in Pa")
    dim.add_argument("--mass", type=real("mass M", positive), help="ball mass M in kg")
    dim.add_argument("--g", type=real("g", positive), help="gravity in m/s^2 (default 9.81)")
    add_compliance_options(p, poisson_help="also the nu of the SI results", traced=False)
    p.set_defaults(run=run)
    return p


def _angles(args) -> tuple[float, float]:
    """``(gamma, delta)`` in radians, checked in the unit they were given in.

    Raises
    ------
    UsageError
        Naming the angle, its value in the unit given and the allowed range in that unit.
    """
    # Imported here, not at the top: the model loads numpy, which `groove --help` does not need.
    from ..model.parameters import check_domain

    gamma, delta = args.gamma + 0.0, args.delta + 0.0  # (-0.0 as 0.0)
    if args.deg:
        # the slack of check_domain in radians (4 eps relative), in the unit given; an angle
        # within it of an edge is taken as on the edge
        slack = 4.0 * sys.float_info.epsilon
        if not 0.0 <= gamma <= 90.0 * (1.0 + slack):
            raise UsageError(f"gamma = {gamma!r} deg is outside the allowed range "
                             "0 <= gamma <= 90 deg (to 4 eps relative, then taken as 90)")
        gamma = min(gamma, 90.0)
        if not 0.0 <= delta <= gamma * (1.0 + slack) + 4.0 * 5e-324:
            raise UsageError(f"delta = {delta!r} deg is outside the allowed range "
                             f"0 <= delta <= gamma (gamma = {gamma!r} deg)")
        delta = min(delta, gamma)
        # radians() is monotonic and maps 90 to the float nearest pi/2, so the check holds.
        gamma, delta = math.radians(gamma), math.radians(delta)
    try:
        check_domain(gamma, delta)
    except ValueError as exc:
        raise UsageError(str(exc)) from None
    return gamma, delta


def run(args) -> int:
    """Solve and print; exit code 0, or :class:`UsageError` for a point outside the domain."""
    # Imported here, not at the top: the solver loads numpy, which `groove --help` should not
    # wait for.
    from ..model.equilibrium import solve_equilibrium
    from ..model.parameters import Parameters

    k = one_friction(args, "solve")
    gamma, delta = _angles(args)
    compliance = compliance_from(args)
    eq = solve_equilibrium(gamma, delta, Parameters(k, compliance))
    dimensional = _dimensional(args, eq)
    if args.json:
        given = {"k": k, "compliance": compliance.ratio}
        out = {key: _json_value(given[key] if key in given else getattr(eq, key))
               for key in JSON_KEYS}
        if dimensional is not None:
            out["dimensional"] = {key: _json_value(v) for key, v in dimensional.to_dict().items()}
        print(json.dumps(out))
        return EXIT_OK
    _print_state(k, eq, dimensional, compliance.ratio, compliance.poisson)
    return EXIT_OK


def _json_value(value):
    """A float as itself (None if not finite), an enum or string as its text."""
    if isinstance(value, str):
        return str(value.value if hasattr(value, "value") else value)
    value = float(value)
    return value if math.isfinite(value) else None


def _dimensional(args, eq):
    """The SI state when all four material options are given, None when none of --radius,
    --young, --mass is (--poisson alone only sets the compliance)."""
    # Imported here for the same reason as the solver in `run`.
    from ..model.dimensional import dimensional_state

    if all(v is None for v in (args.radius, args.young, args.mass)):
        if args.g is not None:
            raise UsageError(f"--g {args.g!r} is used only for the dimensional results: give "
                             "--radius, --young, --poisson and --mass too")
        return None
    if any(v is None for v in (args.radius, args.young, args.poisson, args.mass)):
        raise UsageError("dimensional results need all of --radius, --young, --poisson, --mass")
    gravity = {} if args.g is None else {"g": args.g}  # else dimensional_state's default
    try:
        return dimensional_state(eq, args.radius, args.young, args.poisson, args.mass, **gravity)
    except ValueError as exc:
        raise UsageError(str(exc)) from None


def _print_state(k: float, eq, dimensional, ratio: float = 1.0,
                 poisson: float | None = None) -> None:
    """The state in words; ``gamma`` and ``delta`` in full, so that they can be given back.
    ``poisson``: the Poisson ratio the compliance ratio was computed from, if any."""
    # Imported here for the same reason as the solver in `run`.
    from ..model.parameters import k_text

    compliance = "" if ratio == 1.0 else f", compliance ratio {ratio!r}"
    if compliance and poisson is not None:
        compliance += f" (Mindlin's for nu = {k_text(poisson)})"
    print(f"k = {k_text(k)}{compliance}, gamma = {float(eq.gamma)!r} rad "
          f"({math.degrees(eq.gamma):.6g} deg), delta = {float(eq.delta)!r} rad "
          f"({math.degrees(eq.delta):.6g} deg)")
    print(f"  regime     {eq.regime.replace('_', ' ')}, rotation {eq.rotation}")
    print(f"  theta_L    {eq.theta_L:.10g}   theta_R {eq.theta_R:.10g}")
    print(f"  beta_L     {eq.beta_L:.10g}   beta_R  {eq.beta_R:.10g}")
    print(f"  upsilon    {eq.upsilon:.10g}")
    print(f"  T/N_L      {eq.T_over_N_L:.10g}   T/N_R   {eq.T_over_N_R:.10g}   (k = {k_text(k)})")
    print(f"  d_L/Z      {eq.d_L:.10g}   d_R/Z   {eq.d_R:.10g}")
    if dimensional is not None:
        d = dimensional
        print(f"  Z          {d.Z:.6g} m")
        print(f"  N_L, N_R   {d.N_L:.6g} N, {d.N_R:.6g} N;  T {d.T:.6g} N")
        print(f"  a_L, a_R   {d.a_L:.6g} m, {d.a_R:.6g} m (contact radii)")
