"""Floor motions, in the order they flow into a campaign.

* :mod:`~opsrock.excitations.base`: the :class:`Excitation` protocol every solver reads;
* :mod:`~opsrock.excitations.pulses`: analytic pulses (the paper's one-sine pulse, the rectangular,
  half-sine, one-cosine and Ricker pulses of the rocking literature);
* :mod:`~opsrock.excitations.records`: sampled acceleration histories (:class:`Record`);
* :mod:`~opsrock.excitations.readers`: record files (PEER NGA ``.AT2``, text and CSV);
* :mod:`~opsrock.excitations.library`: named record sets (FEMA P695, optional extra ``records``);
* :mod:`~opsrock.excitations.building`: ground motion to floor motion through a shear building.
"""

from opsrock.excitations.base import Excitation
from opsrock.excitations.pulses import (
    PFV_CONVENTIONS,
    PULSE_SHAPES,
    HalfSinePulse,
    HarmonicPulse,
    OneCosinePulse,
    OneSinePulse,
    Pulse,
    RectangularPulse,
    RickerWavelet,
    pulse_class,
)
from opsrock.excitations.plan import PlanMotion
from opsrock.excitations.records import Record

__all__ = ["Excitation", "HalfSinePulse", "HarmonicPulse", "OneCosinePulse", "OneSinePulse", "PFV_CONVENTIONS", "PULSE_SHAPES", "PlanMotion", "Pulse",
           "Record", "RectangularPulse", "RickerWavelet", "pulse_class"]
