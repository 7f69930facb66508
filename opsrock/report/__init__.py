"""Reports: the computations tied together into documents a reader checks. A report computes nothing:
it is given what the workflow (:mod:`opsrock.analysis.reproduce`) computed, and writes it out.

* :mod:`~opsrock.report.paper`: ``opsrock reproduce``'s ``report.md`` and ``validation_gate.md``, the
  paper's conclusions checked one by one;
* :mod:`~opsrock.report.records`: ``opsrock fragility``'s ``report.md`` (the workflow:
  :mod:`opsrock.analysis.record_report`);
* :mod:`~opsrock.report.markdown`: Markdown tables.
"""
