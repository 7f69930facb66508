"""Model and numerical settings of the scipy SDOF solver."""

from __future__ import annotations

from dataclasses import dataclass, field

from opsrock.errors import InputTypeError
from opsrock.limits import int_at_least, one_of
from opsrock.model import SDOFModel
from opsrock.solvers.common import IVP_METHODS, ScipySettings


@dataclass(frozen=True)
class SDOFSettings(ScipySettings):
    """The SDOF model and the numerics of its scipy integration: those of
    :class:`~opsrock.solvers.common.ScipySettings` and

    Parameters
    ----------
    model : SDOFModel
        The equivalent SDOF model (damper band ``delta``, stiff branch ``theta_e_ratio``, table points,
        lever, damper law), the same object the OpenSees solver takes; its fields may also be given
        by name as overrides (``delta=0.01``).
    method : str
        :func:`scipy.integrate.solve_ivp` method outside the stiff branch. Default ``"DOP853"``: there
        the equation is linear, non-stiff (rates ``p`` and ``c_D / I_O``) and smooth.
    stiff_method : str
        Method inside the stiff branch ``|theta| < theta_e``. Default ``"Radau"`` (implicit, L-stable:
        the branch's ``omega_e`` is ~1000 p).
    atol : float
        Absolute tolerance on ``theta`` (rad); ``atol · p`` on ``theta'``. Default 1e-13 rad, ten times
        below the default ``theta_e`` of a slender block (~2e-7 rad) squared-off by the 1e-6 ratio, so
        the stiff branch is resolved.
    tail : str
        ``"rest"``: after the excitation, integrate until the block is trapped in the damper band (its
        energy ``1/2 I_O theta'² + U(theta)`` below ``U(delta alpha)``, where ``U`` is the table
        spring's potential, so it can never rock out again) or seated; ``"peak"``: stop at the first
        turning point after the excitation with ``|theta| < alpha``.
    max_impacts : int
        Largest number of impacts (band crossings from one side to the other) before the run is
        reported as failed. Default 10 000.
    max_segments : int
        Largest number of region/breakpoint segments before the run is reported as failed. Default
        200 000 (a record of 10 000 samples needs about that many).
    uplift_check : bool
        If True (default), a block starting from rest under an excitation that cannot uplift it (Eq. 4
        for the model's lever, :func:`opsrock.model.can_uplift`) is returned seated without
        integration, as the OpenSees solver does.
    stiff_closed_form : bool
        Under a record (acceleration linear between samples), solve the stiff branch in closed form
        (:mod:`~opsrock.solvers.sdof.closed_form`) instead of with ``stiff_method``. Default True;
        False: the implicit integrator everywhere (the reference of the test that checks the closed form).
    """

    model: SDOFModel = field(default_factory=SDOFModel)
    atol: float = 1e-13
    stiff_method: str = "Radau"
    max_segments: int = 200_000
    uplift_check: bool = True
    stiff_closed_form: bool = True

    def __post_init__(self) -> None:
        super().__post_init__()
        if not isinstance(self.model, SDOFModel):
            raise InputTypeError(f"model must be an SDOFModel, got {self.model!r}")
        one_of("stiff_method", self.stiff_method, IVP_METHODS)
        int_at_least("max_segments", self.max_segments, 1)


__all__ = ["SDOFSettings"]
