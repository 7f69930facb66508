"""Many solves of one block, with a question behind them.

* :mod:`~opsrock.analysis.threshold`: every amplitude interval in which a block overturns under a
  pulse (the minimum overturning acceleration and the safe windows above it), and whole charts;
* :mod:`~opsrock.analysis.sensitivity`: how far the answer moves when the floor motion or the
  numerics move a little (the test for hypersensitive, ill-conditioned cases);
* :mod:`~opsrock.analysis.robustness`: is an IM ranking a property of the IMs or of the blocks?
  The paper's pulse study repeated over many seeded block sets;
* :mod:`~opsrock.analysis.reproduce`: ``opsrock reproduce``, the paper's workflow from the validation
  gate to the figures and the report;
* :mod:`~opsrock.analysis.record_report`: ``opsrock fragility``, the record fragility workflow of a record
  campaign, from its ``cases.csv`` to the figures and the report.
* :mod:`~opsrock.analysis.record_columns`: the unit of every column of ``opsrock fragility``'s tables, and their
  writer and reader with a units row.
"""
