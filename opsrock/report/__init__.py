"""Reports: the computations tied together into documents a reader checks.

* :mod:`~opsrock.report.reproduce`: ``opsrock reproduce``, the paper's workflow from the validation
  gate to the figures;
* :mod:`~opsrock.report.paper`: its ``report.md``, the paper's conclusions checked one by one;
* :mod:`~opsrock.report.records`: ``opsrock fragility``, the record fragility report;
* :mod:`~opsrock.report.markdown`: Markdown tables.
"""
