"""Parameter limits of opsrock's inputs, declared in one place, and the checks every input goes through.

Every input class checks its numbers against this table (:func:`check`), so a value outside the
range the models and solvers were built and tested for is refused with one line naming the
argument, its value and the range, instead of overflowing or running for hours later on.

The limits are generous: they bound what the physics and floating point can carry, not what
is typical. Each states its reason.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from numbers import Integral, Real

from opsrock.constants import G, OVERTURNING_ANGLE
from opsrock.errors import ImplausibleInputError, InputError, InputTypeError


@dataclass(frozen=True)
class Limit:
    """A closed range ``[low, high]`` for one named input.

    Parameters
    ----------
    low, high : float
        Smallest and largest accepted value, in ``unit``.
    unit : str
        Unit of the value (SI), for the message.
    why : str
        Reason for the range.
    """

    low: float
    high: float
    unit: str
    why: str


#: The limits, by argument name.
LIMITS: dict[str, Limit] = {
    "width": Limit(1e-3, 1e3, "m", "a rigid block from 1 mm to 1 km; beyond, R² and I_O overflow or underflow"),
    "height": Limit(1e-3, 1e3, "m", "as width"),
    "mass": Limit(1e-6, 1e12, "kg", "mass only scales moments; kept where m g R² stays finite"),
    "pfa": Limit(1e-9, 1e4, "m/s²", "up to about 1,000 g; beyond, no floor motion is physical"),
    "omega_p": Limit(1e-3, 1e5, "rad/s",
                     "pulse periods from 63 µs to 1.7 h: a longer pulse is a static tilt, a shorter one "
                     "cannot be sampled by any solver's step"),
    "duration": Limit(1e-6, 1e5, "s", "pulse and record durations from 1 µs to about 28 h"),
    "dt": Limit(1e-7, 1.0, "s", "record sample intervals: below 1e-7 s no accelerograph samples, above 1 s no "
                "floor motion is resolved"),
    "step": Limit(1e-7, 1.0, "s", "solver time steps: below 1e-7 s the OpenSees model's smallest step min_step "
                  "cannot fit, above 1 s no pulse or record is resolved"),
    "scale": Limit(1e-2, 1e2, "-",
                   "record scale factors: beyond x100 (or below x0.01) a record no longer stands for "
                   "a motion of its kind; FEMA P695 and IDA practice stay well inside"),
    "record_dt_p": Limit(0.0, 0.2, "-",
                         "record sample interval times the block's p: the block's motion evolves on the "
                         "time scale 1/p, and the piecewise-linear record must sample it at least five "
                         "times per 1/p, or steps bound to the samples jump over impacts"),
    "friction": Limit(0.0, 100.0, "-", "static Coulomb friction coefficient of the block on the floor: 0 is "
                      "frictionless; above about 1 no floor motion makes a block slide"),
    "friction_kinetic": Limit(0.0, 1.3, "-", "kinetic Coulomb friction coefficient: below 4/3, where the "
                              "slide-rock equations of a rectangle stop having one solution (Painlevé)"),
    "vertical": Limit(-9.8, 1e3, "m/s²", "a constant vertical floor acceleration (positive up) must leave the "
                      "block some weight, g + a_v > 0; above 100 g no floor moves"),
    "period": Limit(1e-2, 10.0, "s", "first periods of buildings, from very stiff (0.01 s) to very flexible (10 s)"),
    "damping": Limit(0.0, 0.5, "-", "viscous damping ratio of a building's modes; above 0.5 no building is linear"),
    "storeys": Limit(1, 200, "-", "storeys of a shear building: the filter's cost grows faster than the storeys "
                     "(200 storeys take 16.5 s on a 20-s record, 2 cores; opsrock.excitations.building.MAX_STOREYS)"),
    # --- counts, tolerances and budgets: what a 2-core machine finishes in reasonable time -------------
    "n_boot": Limit(0, 10_000, "-", "bootstrap resamples of a fragility fit: 200 give intervals to about 1 %; "
                    "10,000 take about an hour for nine IMs on a 3,520-case campaign"),
    "robustness_sets": Limit(0, 5_000, "-", "seeded block sets of the ranking-robustness study: 200 take 38 s "
                             "on 2 cores, 5,000 about 16 min"),
    "n_scan": Limit(3, 100_000, "-", "amplitudes scanned by the threshold search: 600 resolve 0.65 % steps; "
                    "100,000 solves take minutes with housner_fast, hours with the SDOF models"),
    "boundary_rtol": Limit(1e-12, 0.1, "-", "relative width of a refined overturning boundary: below 1e-12 the "
                           "bisection works on round-off, above 0.1 it is not a boundary"),
    "seed": Limit(0, 2**32 - 1, "-", "seeds of numpy's random generator, as unsigned 32-bit integers"),
    "workers": Limit(1, 1024, "-", "worker processes or threads: at least one, at most what any machine has"),
    "batch": Limit(1, 1_000_000, "-", "cases per batch of a campaign"),
    "case_timeout": Limit(1e-3, 1e6, "s", "wall-clock budget of one case: from 1 ms to about 11 days (the "
                          "slowest healthy case measured takes 17 s)"),
    "quantity": Limit(1, 1_000_000, "-", "units of one inventory item on one floor, a whole number: a million "
                      "of one item on one floor is beyond any building (a larger count is a unit or typing mistake)"),
    "inventory_items": Limit(1, 10_000, "-", "one row per item type, each fitted on its own (16 IDA levels x every "
                             "record, floor and direction each): 10,000 types are beyond any building's contents and "
                             "already millions of cases; split the inventory or group its items by type"),
    "record_file_bytes": Limit(0, 64e6, "B", "size of a record file: 64 MB hold 4 million samples, 40 times "
                               "the longest FEMA P695 record at 0.001 s; larger files are refused unread"),
}


@dataclass(frozen=True)
class Plausible:
    """A bound that no real input reaches although the physics allows it: beyond it the value is refused as a
    likely unit mistake unless the user confirms it (:func:`check_plausible`).

    Parameters
    ----------
    high : float
        The bound, in ``unit``.
    unit : str
        Its SI unit.
    reason : str
        Why no real input reaches it (one line, for docs and messages).
    typical : float
        A typical value (``unit``): of the units a refused value may have been meant in
        (:data:`LIKELY_UNITS`), the one that brings it nearest to this (in ratio) is named as the likely cause.
    """

    high: float
    unit: str
    reason: str
    typical: float = 1.0


#: Plausibility bounds, declared once; every user boundary (command line, scene, inventory, motions
#: manifest, record files) checks against these (:func:`check_plausible`,
#: :func:`opsrock.excitations.records.check_plausible_record`).
PLAUSIBLE: dict[str, Plausible] = {
    "pfa": Plausible(10.0 * G, "m/s²", "no recorded floor or ground motion reaches 10 g (the largest "
                     "recorded ground accelerations are about 4 g)", typical=0.3 * G),
    "block_size": Plausible(10.0, "m", "no piece of furniture or equipment is larger than 10 m in any "
                            "dimension", typical=1.0),
}

#: The units a value of each plausibility bound's quantity may be given or meant in, with the factor to its SI
#: unit (ASCII names, as ``--units`` takes them); the SI unit itself first.
LIKELY_UNITS: dict[str, dict[str, float]] = {
    "pfa": {"m/s2": 1.0, "g": G, "cm/s2": 0.01, "mm/s2": 0.001},
    "block_size": {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": 0.0254},
}

#: The command-line option that confirms implausible values (``simulate``, ``threshold``, ``run``, ``records``).
ACCEPT_OPTION: str = "--accept-implausible"

#: The scene key that confirms them (top level of a scene file; ``run`` takes :data:`ACCEPT_OPTION` too).
ACCEPT_KEY: str = "accept_implausible = true"

#: How a unit is named in a message.
UNIT_WORDS: dict[str, str] = {"m/s2": "m/s²", "cm/s2": "cm/s²", "mm/s2": "mm/s²", "g": "g", "m": "m",
                              "cm": "centimetres", "mm": "millimetres", "in": "inches"}

#: A record given without its units (:class:`~opsrock.excitations.records.Record` with ``units=None``) whose
#: peak lies strictly between 0 and this (m/s²) looks like g and is refused until its units are stated. In
#: g, the motions opsrock analyses peak between about 0.05 and 4 g, so their numbers in g lie below 1 (every
#: FEMA P695 far-field component, 52 of the 56 near-field ones). In m/s², a peak below 1 m/s² (0.102 g)
#: cannot uplift a block with ``b/h`` above 0.102 (uplift needs ``PFA > g b/h``; every shipped block is
#: stockier, the slenderest has ``b/h`` = 0.155) nor make a block slide on a friction coefficient above 0.102
#: (furniture on floors: 0.2-0.6). Read as m/s², such a record moves nothing; read as g, it is an ordinary
#: motion.
G_LIKE_PEAK: float = 1.0


def likely_unit(name: str, value: float, declared: str, among: tuple[str, ...] | None = None
                ) -> tuple[str, float] | None:
    """The unit ``value`` was most likely meant in, if not ``declared``: ``(unit, SI value)`` or None.

    Parameters
    ----------
    name : str
        A key of :data:`PLAUSIBLE`.
    value : float
        The value in its SI unit (m/s², m), as read with ``declared``.
    declared : str
        The unit it was given in, a key of ``LIKELY_UNITS[name]``.
    among : tuple of str, optional
        The units to try (those the user can give, e.g. the record units ``g``, ``m/s2``, ``cm/s2``); default
        every unit of ``LIKELY_UNITS[name]``.

    Returns
    -------
    tuple or None
        Of the other units in which the number as written is plausible, the one nearest (in ratio) to the
        bound's typical value; None if none is.
    """
    bound, units = PLAUSIBLE[name], LIKELY_UNITS[name]
    written = abs(value) / units[declared]
    if written == 0.0 or not math.isfinite(written):
        return None
    plausible = [(u, written * f) for u, f in units.items()
                 if u != declared and (among is None or u in among) and written * f <= bound.high]
    if not plausible:
        return None
    return min(plausible, key=lambda uv: abs(math.log(uv[1] / bound.typical)))


def unit_symbol(unit: str) -> str:
    """The symbol of a unit of :data:`LIKELY_UNITS` as printed (``"cm/s2"`` -> ``"cm/s²"``)."""
    return unit.replace("s2", "s²")


def implausible_message(name: str, value: float, *, what: str, declared: str, option: str,
                        fix: str | None = None, among: tuple[str, ...] | None = None) -> str:
    """The one line that refuses ``value`` (SI) beyond ``PLAUSIBLE[name]``: the value as written in
    ``declared``, the bound and why, the likely unit with ``fix`` for it (default: give the value in
    ``declared``, converted), and the confirming ``option``. ``fix`` given (a template of ``{unit}``, the likely
    unit's ASCII name): the value is a record's values ("the values look like cm/s² declared as g: give
    --units cm/s2", from ``"give --units {unit}"``), and the likely unit is one of
    ``among`` (:func:`likely_unit`)."""
    bound, factor = PLAUSIBLE[name], LIKELY_UNITS[name][declared]
    d, si = unit_symbol(declared), unit_symbol(next(iter(LIKELY_UNITS[name])))
    written = value / factor
    shown = f"{written:.4g} {d}" + ("" if factor == 1.0 else f" ({value:.4g} {si})")
    likely = likely_unit(name, value, declared, among)
    if likely is None:
        cause = f"check its unit ({d})"
    else:
        u, meant = likely
        same = f"{abs(written):.4g} {unit_symbol(u)}" + ("" if unit_symbol(u) == si else f" = {meant:.4g} {si}")
        cause = (f"the values look like {UNIT_WORDS[u]} declared as {d} ({same}): {fix.format(unit=u)}" if fix else
                 f"it looks like {UNIT_WORDS[u]}, not {d} ({same}): give it in {d} ({meant / factor:.4g})")
    return (f"{what} = {shown} exceeds {bound.high / factor:.4g} {d}: {bound.reason}; {cause}, "
            f"or confirm it with {option}")


def check_plausible(name: str, value: float, *, what: str, option: str, confirm: bool = False,
                    declared: str | None = None) -> None:
    """Refuse ``value`` (SI) beyond ``PLAUSIBLE[name]`` unless ``confirm``, naming its likely cause.

    Parameters
    ----------
    name : str
        A key of :data:`PLAUSIBLE` (``"pfa"``, ``"block_size"``).
    value : float
        The value, in the bound's SI unit (m/s², m).
    what : str
        What the value is and where it came from, for the message (``"--width"``, ``"motions.csv line 3
        (rec1.csv): PFA"``).
    option : str
        How the user confirms it (``"--accept-implausible"``, ``"accept_implausible = true"``).
    confirm : bool
        True: the user has confirmed the value; nothing is checked.
    declared : str, optional
        The unit the user gave the value in, a key of ``LIKELY_UNITS[name]`` (``"g"`` for ``--pfa``); default
        the SI unit. The message shows the value as written and names the unit it was more likely meant in.

    Raises
    ------
    ImplausibleInputError
        One line: the value, the bound and why, the likely unit and the fix.
    """
    if confirm or not math.isfinite(value) or abs(value) <= PLAUSIBLE[name].high:
        return
    declared = declared or next(iter(LIKELY_UNITS[name]))
    raise ImplausibleInputError(implausible_message(name, value, what=what, declared=declared, option=option),
                                argument=what)


def check_plausible_sizes(sizes: dict[str, float], *, option: str, confirm: bool = False) -> None:
    """:func:`check_plausible` of every block dimension in ``sizes`` (``{what: value in m}``, e.g.
    ``{"--width": 0.4, "--height": 2.2}``), in order: the first beyond ``PLAUSIBLE["block_size"]`` is refused
    unless ``confirm``, naming the unit it looks like (millimetres, centimetres, inches)."""
    for what, value in sizes.items():
        check_plausible("block_size", value, what=what, option=option, confirm=confirm)


def shown(value: object) -> str:
    """``repr`` of a value for a message, numpy scalars as plain Python numbers (``1e+300``, not
    ``np.float64(1e+300)``)."""
    if type(value).__module__ == "numpy" and hasattr(value, "item"):
        value = value.item()
    return repr(value)


def check(name: str, value: object, *, shown_as: str | None = None) -> float:
    """Return ``value`` as a float if it is a real number within ``LIMITS[name]``.

    Parameters
    ----------
    name : str
        A key of :data:`LIMITS`; the argument named in the message unless ``shown_as`` is given.
    value : object
        The value to check (bool is refused).
    shown_as : str, optional
        The name the user gave it (``"--n-boot"``), for the message.

    Raises
    ------
    TypeError
        If ``value`` is not a real number.
    ValueError
        If it is not finite or lies outside the limit; the message names ``name``, the value and
        the range with its unit.
    """
    limit = LIMITS[name]
    label = shown_as or name
    v = real_number(label, value)
    if not math.isfinite(v) or not (limit.low <= v <= limit.high):
        unit = "" if limit.unit == "-" else f" {limit.unit}"
        raise InputError(f"{label} must lie in [{limit.low:g}, {limit.high:g}]{unit}, got {shown(value)}"
                         + _unit_hint(name, v))
    return v


#: Limits whose quantity has a plausibility bound: a value beyond the limit is named with its likely unit too.
_PLAUSIBLE_OF: dict[str, str] = {"width": "block_size", "height": "block_size"}


def _unit_hint(name: str, value: float) -> str:
    """``"; it looks like millimetres (2500 mm = 2.5 m)"`` for a block dimension beyond its limit, else ``""``."""
    quantity = _PLAUSIBLE_OF.get(name)
    likely = None if quantity is None or not math.isfinite(value) else likely_unit(quantity, value, "m")
    if likely is None:
        return ""
    return f"; it looks like {UNIT_WORDS[likely[0]]} ({abs(value):g} {likely[0]} = {likely[1]:.4g} m)"


def check_count(name: str, value: object, *, shown_as: str | None = None) -> int:
    """Return ``value`` if it is an integer (bool refused) within ``LIMITS[name]``; as :func:`check`."""
    label = shown_as or name
    if isinstance(value, bool) or not isinstance(value, Integral):
        raise InputError(f"{label} must be an integer, got {shown(value)}")
    limit = LIMITS[name]
    if not limit.low <= value <= limit.high:
        raise InputError(f"{label} must be an integer in [{int(limit.low)}, {int(limit.high)}], got {shown(value)}")
    return int(value)


def scaled_input(name: str, value: float, target: str, scale: float) -> float:
    """``value * scale`` checked against the limit of ``target``, with a message naming ``name``.

    Parameters
    ----------
    name : str
        The argument the user gave (``"pfa_ratio"``, ``"--freq"``), named in the message.
    value : float
        Its value (its own unit).
    target : str
        The checked quantity, a key of :data:`opsrock.limits.LIMITS`.
    scale : float
        Factor from ``value`` to ``target``'s SI unit.
    """
    try:
        return check(target, value * scale)
    except ValueError:
        lim = LIMITS[target]
        raise InputError(
            f"{name} = {value!r} gives {target} = {value * scale:.4g} {lim.unit}, outside "
            f"[{lim.low:g}, {lim.high:g}] {lim.unit}"
        ) from None


# --- checks shared by the dataclasses: every error names the argument and its value -------------
def real_number(name: str, value: object) -> float:
    """Return ``value`` as a float, or raise ``TypeError`` naming ``name`` if it is not a real
    number (bool is refused), ``ValueError`` if it does not fit a float."""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise InputTypeError(f"{name} must be a real number, got {shown(value)} ({type(value).__name__})")
    try:
        return float(value)
    except (OverflowError, ValueError):
        raise InputError(f"{name} must be a finite number, got {shown(value)}") from None


def initial_state(theta0: object, theta_dot0: object) -> tuple[float, float]:
    """``(theta0, theta_dot0)`` as floats, or raise naming the one that is not a start of rocking:
    ``theta0`` (rad) finite with ``|theta0| < pi/2``, ``theta_dot0`` (rad/s) finite."""
    th0, thd0 = real_number("theta0", theta0), real_number("theta_dot0", theta_dot0)
    if not (math.isfinite(th0) and abs(th0) < OVERTURNING_ANGLE):
        raise InputError(f"theta0 must be finite with |theta0| < pi/2, got {theta0!r}")
    if not math.isfinite(thd0):
        raise InputError(f"theta_dot0 must be finite, got {theta_dot0!r}")
    return th0, thd0


def compiled_stepping(settings: object) -> None:
    """Check the stepping fields the compiled event-driven solvers share (``housner_fast``, ``friction``):
    ``max_dtau`` in (0, 0.5] (units of 1/p), ``steps_per_pulse`` >= 8, ``rest_velocity`` in (0, 1e-3]
    (units of p), ``max_impacts`` and ``max_steps`` >= 1 (no unit; None: the solver's default)."""
    s = settings
    positive_finite("max_dtau", s.max_dtau)
    if s.max_dtau > 0.5:
        raise InputError(f"max_dtau must be <= 0.5 (units of 1/p), got {s.max_dtau!r}")
    int_at_least("steps_per_pulse", s.steps_per_pulse, 8)
    positive_finite("rest_velocity", s.rest_velocity)
    if s.rest_velocity > 1e-3:
        raise InputError(f"rest_velocity must be <= 1e-3 (units of p), got {s.rest_velocity!r}")
    int_at_least("max_impacts", s.max_impacts, 1)
    if s.max_steps is not None:
        int_at_least("max_steps", s.max_steps, 1)


def positive_finite(name: str, value: object) -> float:
    """Return ``value`` as a float, or raise ``ValueError`` naming ``name`` and the value.

    Parameters
    ----------
    name : str
        Argument name used in the message.
    value : object
        Value to check; must be a real, finite, strictly positive number (bool is refused).
    """
    v = real_number(name, value)
    if not math.isfinite(v) or v <= 0.0:
        raise InputError(f"{name} must be positive and finite, got {value!r}")
    return v


def positive_at_most(name: str, value: object, high: float, unit: str = "") -> float:
    """Return ``value`` as a positive finite float not above ``high``, else raise naming ``name`` (``unit``: the
    bound's unit in the message, e.g. ``" (units of 1/p)"``)."""
    v = positive_finite(name, value)
    if v > high:
        raise InputError(f"{name} must be <= {high:g}{unit}, got {value!r}")
    return v


def in_open_interval(name: str, value: object, low: float, high: float) -> float:
    """Return ``value`` as a float if ``low < value < high``, else raise naming ``name``."""
    v = real_number(name, value)
    if not (math.isfinite(v) and low < v < high):
        raise InputError(f"{name} must lie in ({low:g}, {high:g}), got {value!r}")
    return v


def one_of(name: str, value: object, allowed: tuple[str, ...]) -> str:
    """Return ``value`` if it is one of ``allowed``, else raise naming ``name``."""
    if value not in allowed:
        raise InputError(f"{name} must be one of {', '.join(map(repr, allowed))}; got {value!r}")
    return value  # type: ignore[return-value]


def int_at_least(name: str, value: object, minimum: int = 1) -> int:
    """Return ``value`` if it is an int >= ``minimum``, else raise naming ``name``."""
    if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
        raise InputError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return value


def bool_fields(obj: object) -> None:
    """Raise ``TypeError`` naming the first field of dataclass ``obj`` declared ``bool`` whose value
    is not a bool (``"no"``, ``0`` and ``None`` are refused, never read as true or false)."""
    from dataclasses import fields

    for f in fields(obj):  # type: ignore[arg-type]
        if f.type in ("bool", bool):
            value = getattr(obj, f.name)
            if not isinstance(value, bool):
                raise InputTypeError(f"{f.name} must be true or false (a bool), got {value!r}")


__all__ = ["ACCEPT_KEY", "ACCEPT_OPTION", "G_LIKE_PEAK", "LIKELY_UNITS", "LIMITS", "Limit", "PLAUSIBLE", "Plausible", "UNIT_WORDS", "check_plausible",
           "check_plausible_sizes", "implausible_message", "likely_unit", "unit_symbol", "bool_fields", "check", "check_count", "compiled_stepping", "in_open_interval", "initial_state", "int_at_least", "one_of",
           "positive_at_most", "positive_finite", "real_number", "scaled_input", "shown"]
