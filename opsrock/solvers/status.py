"""The statuses every solver shares, and the one layout of the compiled kernels' output array.

A run ends in one of :data:`CODES` (integers, so the numba kernels return them as they are); the Python
side turns a code into :attr:`opsrock.result.RockingResult.failure` (a kind, :data:`FAILURES`) and a
``reason`` (:data:`REASONS`, to which a solver may append where and when). ``OK`` is the one success.

The compiled kernels (``housner_fast``, ``friction``, ``moreau_jean``) write one float vector per case
whose first :data:`OUT_COMMON` slots mean the same in each (``OUT_STATUS`` ... ``OUT_EVENT_TIME``); a
kernel's own quantities follow from ``OUT_COMMON`` on. Nothing here imports numba: the integer
constants are read by the kernels as compile-time globals.
"""

from __future__ import annotations

# --- status codes -----------------------------------------------------------------------------------
#: Finished: the verdict (no uplift, safe or overturned) holds.
OK = 0
#: More impacts than ``max_impacts`` without coming to rest.
MAX_IMPACTS = 1
#: A non-finite state (rotation, velocity, position) appeared.
NONFINITE = 2
#: More steps than ``max_steps``.
MAX_STEPS = 3
#: An event (impact, peak, stick-slip) could not be located.
EVENT_FAILED = 4
#: The impact law had no solution with compressive impulses.
IMPACT_LAW = 5
#: The block was still moving ``max_free_time`` after the excitation ended (or at a hard ``end_time``
#: of a solver that must reach rest).
MAX_FREE_TIME = 6
#: The contact problem of a time step had no solution.
NO_CONTACT_SOLUTION = 7
#: More wall-clock time than ``max_wall_time`` (or the campaign's case timeout).
TIMEOUT = 8
#: The integrator failed (a step that could not be recovered, scipy's ``solve_ivp`` failure).
INTEGRATOR = 9
#: A scheme used outside its stability limit (explicit OpenSees steps).
UNSTABLE = 10
#: Anything else: an exception inside the solver, turned into a failed result.
ERROR = 11

#: Every status code with its failure kind (:attr:`RockingResult.failure`; None for ``OK``).
FAILURES: dict[int, str | None] = {
    OK: None,
    MAX_IMPACTS: "max_impacts",
    NONFINITE: "nonfinite",
    MAX_STEPS: "max_steps",
    EVENT_FAILED: "event_failed",
    IMPACT_LAW: "impact_law",
    MAX_FREE_TIME: "max_free_time",
    NO_CONTACT_SOLUTION: "no_contact_solution",
    TIMEOUT: "timeout",
    INTEGRATOR: "integrator",
    UNSTABLE: "unstable",
    ERROR: "error",
}

#: The failure kinds, in code order (what :attr:`RockingResult.failure` may hold besides None).
FAILURE_KINDS: tuple[str, ...] = tuple(k for k in FAILURES.values() if k is not None)

#: Every code with its reason (the solver may append where and when).
REASONS: dict[int, str] = {
    OK: "",
    MAX_IMPACTS: "max_impacts reached without the block coming to rest",
    NONFINITE: "non-finite state",
    MAX_STEPS: "max_steps reached before the end of the run",
    EVENT_FAILED: "event location did not converge",
    IMPACT_LAW: "the impact law has no solution with compressive impulses (a landing corner of a block "
                "without friction would need a pulling impulse to stick: give the block a finite friction)",
    MAX_FREE_TIME: "the block was still moving max_free_time after the end of the excitation",
    NO_CONTACT_SOLUTION: "the contact problem of a step had no solution (open, stick or slip at each corner)",
    TIMEOUT: "timeout: max_wall_time reached",
    INTEGRATOR: "the integrator failed",
    UNSTABLE: "unstable scheme",
    ERROR: "solver error",
}

#: The compiled kernels' statuses as they name them (the same codes).
CODES: dict[str, int] = {kind: code for code, kind in FAILURES.items() if kind is not None} | {"ok": OK}


def failure_of(code: int) -> str | None:
    """The failure kind of status ``code`` (None: ``OK``)."""
    return FAILURES[int(code)]


# --- the compiled kernels' output vector --------------------------------------------------------------
#: Status code (one of the above).
OUT_STATUS = 0
#: Peak ``|theta|`` (rad).
OUT_THETA_MAX = 1
#: 1.0 if the block overturned.
OUT_OVERTURNED = 2
#: 1.0 if the block rocked (a corner lifted).
OUT_ROCKED = 3
#: Impacts counted.
OUT_IMPACTS = 4
#: Steps taken.
OUT_STEPS = 5
#: Rows written into the history arrays.
OUT_N_HIST = 6
#: Time of the event that ended the run, in the kernel's time unit (``1/p``): where a failure happened.
OUT_EVENT_TIME = 7
#: First slot of a kernel's own quantities.
OUT_COMMON = 8


__all__ = ["CODES", "EVENT_FAILED", "ERROR", "FAILURES", "FAILURE_KINDS", "IMPACT_LAW", "INTEGRATOR",
           "MAX_FREE_TIME", "MAX_IMPACTS", "MAX_STEPS", "NONFINITE", "NO_CONTACT_SOLUTION", "OK", "OUT_COMMON",
           "OUT_EVENT_TIME", "OUT_IMPACTS", "OUT_N_HIST", "OUT_OVERTURNED", "OUT_ROCKED", "OUT_STATUS",
           "OUT_STEPS", "OUT_THETA_MAX", "REASONS", "TIMEOUT", "UNSTABLE", "failure_of"]
