"""Named physical and model constants (SI units).

Every number the physics needs lives here with its source, so a reader never meets a bare
literal in the solvers.
"""

from __future__ import annotations

#: Gravitational acceleration (m/s²), the value docs/guide/modelling.md section 2 fixes for the project.
G: float = 9.81

#: Ratio of the restitution coefficient used to the rigid-body one, ``e = 0.95 e_R``
#: (paper, Section 2.1, below Eq. 9).
DEFAULT_RESTITUTION_FACTOR: float = 0.95

#: Overturning limit state on ``|theta|`` (rad), paper Eq. 11.
OVERTURNING_ANGLE: float = 1.5707963267948966  # pi / 2

#: Forms of the rigid-body equation the rigid-body solvers offer. ``"exact"``: Eq. 1,
#: ``theta'' = -p² [sin(alpha s - theta) + a/g cos(alpha s - theta)]``, uplift when
#: ``|a| > g tan(alpha)``. ``"linearised"``: the small-angle form of the classical rocking papers
#: (Housner 1963 onwards), ``theta'' = -p² [(alpha s - theta) + a/g]``, uplift when ``|a| > g alpha``;
#: its free-rocking energy is ``theta'²/(2p²) + [alpha² - (alpha - |theta|)²]/2``.
EQUATIONS: tuple[str, ...] = ("exact", "linearised")

#: The analytic pulse shapes by name, in the order of :data:`opsrock.excitations.PULSE_SHAPES` (which maps each
#: to its class and is built from this tuple): here, so that the command line's parser names them without loading
#: numpy with the pulses.
PULSE_SHAPE_NAMES: tuple[str, ...] = ("rectangular", "half-sine", "one-sine", "one-cosine", "ricker")
