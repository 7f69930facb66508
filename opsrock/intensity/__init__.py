"""Intensity measures: the paper's Table 1 for pulses (:mod:`~opsrock.intensity.table1`) and the
measures of recorded floor motions with Table 1 generalised to them
(:mod:`~opsrock.intensity.records`)."""

from opsrock.intensity.table1 import (
    IM8_RESTITUTION_EXPONENT,
    IM_NAMES,
    IMS,
    IntensityMeasure,
    add_intensity_measures,
    get_im,
    intensity_measures,
    intensity_measures_array,
)

__all__ = ["IM8_RESTITUTION_EXPONENT", "IM_NAMES", "IMS", "IntensityMeasure", "add_intensity_measures",
           "get_im", "intensity_measures", "intensity_measures_array"]
