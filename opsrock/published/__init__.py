"""Published results of the rocking literature, one module per paper (named for it).

Each module holds the paper's closed-form relation (derived again here, in our own words, for the
pulse it studies), the parameter range in which it applies, and the values the paper reports, each
with its source and the tolerance a comparison may use and why. Validation case 7
(:mod:`opsrock.validation.published_thresholds`) compares the solvers against them.

* :mod:`~opsrock.published.housner_1963`: rectangular pulse, linearised equation;
* :mod:`~opsrock.published.makris_roussos_2000`: half-sine pulse, linearised, no impact;
* :mod:`~opsrock.published.zhang_makris_2001`: one-sine pulse, both overturning branches, and the
  locomotive example;
* :mod:`~opsrock.published.makris_konstantinidis_2003`: one-cosine pulse, ``T_p = 2 s``, ``alpha = 15°``;
* :mod:`~opsrock.published.liu_huang_liu_2023`: the reproduced paper's Tables 2 and 3;
* :mod:`~opsrock.published.shenton_1996`: the initiation of rest, slide, rock and slide-rock of a block
  with friction (validation case ``friction``);
* :mod:`~opsrock.published.newmark_1965`: the rigid-plastic sliding block under rectangular and
  half-sine pulses (validation case ``friction``);
* :mod:`~opsrock.published.colombo_limestone`: Colombo et al.'s measured free rocking of limestone blocks
  (the shipped tables; validation case ``experiments`` and the restitution law ``colombo-limestone``);
* :mod:`~opsrock.published.fema_p58`: FEMA P-58's overturning medians of unanchored contents in peak
  floor velocity, and the rule we read behind them (the contents study, ``opsrock contents``);
* :mod:`~opsrock.published.linearised`: the linearised equation under the harmonic pulses solved in
  closed form, independently of the solvers, which the papers' modules share.
"""

from opsrock.published.reference import PublishedValue

__all__ = ["PublishedValue"]
