"""The minimum-overturning charts of the rocking literature, computed with our solver.

Four panels, one per classical pulse: Housner's rectangular pulse, Makris and Roussos' half-sine,
Zhang and Makris' one-sine (both overturning branches and the safe window between them) and Makris
and Konstantinidis' one-cosine: every overturning interval that :func:`opsrock.analysis.threshold.threshold_chart`
finds (``housner_fast``, linearised equation, as the papers solve it), at many ``omega_p / p``.
:mod:`opsrock.plots.thresholds` draws them beside the papers' closed forms.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from opsrock.analysis.threshold import threshold_chart
from opsrock.block import Block

#: Block of the charts (2b x 2h = 0.5 x 2 m, alpha = 0.245 rad). Under the linearised equation the
#: charts, in ``a / (g alpha)`` against ``omega_p / p``, do not depend on the block but through ``e``.
CHART_BLOCK: tuple[float, float] = (0.5, 2.0)

#: Upper end of the drawn amplitude axis, ``a / (g alpha)``.
Y_MAX: float = 20.0



@dataclass(frozen=True)
class ChartData:
    """The overturning intervals of one panel, in ``a / (g alpha)``, per ``omega_p / p``."""

    shape: str
    restitution: float
    freq_ratio: np.ndarray
    intervals: tuple[tuple[tuple[float, float], ...], ...]
    n_solves: int
    wall_time_s: float


def chart_data(shape: str, restitution: float, freq_ratios: np.ndarray, *, n_scan: int = 300) -> ChartData:
    """Overturning intervals (linearised, ``housner_fast``) at every ``omega_p / p`` of ``freq_ratios``."""
    block = Block(*CHART_BLOCK, restitution=restitution)
    t0 = time.perf_counter()
    # pfa_ratio = (a / g alpha) alpha / tan alpha: scan up to Y_MAX in a / (g alpha)
    top = 1.02 * Y_MAX * block.alpha / block.tan_alpha
    res = threshold_chart(block, freq_ratios, shape=shape, equations="linearised", pfa_ratio_max=top, n_scan=n_scan)
    wall = time.perf_counter() - t0
    ivs = tuple(tuple((r.to_g_alpha(a), r.to_g_alpha(b)) for a, b in r.intervals) for r in res)
    return ChartData(shape, restitution, np.asarray(freq_ratios, dtype=float), ivs,
                     sum(r.n_solves for r in res), wall)


def literature_charts(n: int = 200, n_scan: int = 300) -> dict[str, ChartData]:
    """The data of the four panels: ``n`` frequencies from 0.5 to 20 (rectangular: ``p t_1`` 0.16 to 6.3)."""
    from opsrock.published import makris_konstantinidis_2003 as mk

    nu = np.geomspace(0.5, 20.0, n)
    return {
        "rectangular": chart_data("rectangular", 0.9, nu, n_scan=n_scan),
        "half-sine": chart_data("half-sine", 0.9, nu, n_scan=n_scan),
        "one-sine": chart_data("one-sine", 0.9, nu, n_scan=n_scan),
        "one-cosine": chart_data("one-cosine", mk.restitution(), nu, n_scan=n_scan),
    }


__all__ = ["CHART_BLOCK", "ChartData", "Y_MAX", "chart_data", "literature_charts"]
