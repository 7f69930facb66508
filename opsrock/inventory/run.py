"""One way into the contents study: :func:`run_study` takes what ``opsrock contents`` takes (an inventory file, a
motions manifest, or neither) and runs the same configuration the command runs for it; :func:`run_design` runs a
design already built (the command line's handler builds one with its options' names on every refusal).

Which configuration (:class:`~opsrock.inventory.stages.Route`) runs is read from the design (:func:`route_of`), never
chosen twice:

* :class:`~opsrock.inventory.study.InventoryDesign` with a planar solver: :data:`~opsrock.inventory.study.PLANAR`
  (each item per axis); with a solver in plan (registry ``plan``): :data:`~opsrock.inventory.three_d.THREE_D`;
  with ``side_by_side``: both, :data:`~opsrock.inventory.side_by_side.SIDE_BY_SIDE`;
* :class:`~opsrock.inventory.fema.design.ContentsDesign` (the FEMA P-58 preset):
  :data:`~opsrock.inventory.fema.study.FEMA_NINE`;
* :class:`~opsrock.inventory.directionality.study.DirectionalityDesign` (both models side by side):
  :data:`~opsrock.inventory.directionality.study.BOTH`.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

from opsrock.errors import InputError
from opsrock.inventory.directionality.study import BOTH, DirectionalityDesign
from opsrock.inventory.directionality.study import quick as quick_both
from opsrock.inventory.fema.design import SWEEP_BUILDINGS, ContentsDesign
from opsrock.inventory.fema.design import quick as quick_fema
from opsrock.inventory.campaigns import StudyOptions
from opsrock.inventory.fema.study import FEMA_NINE
from opsrock.inventory.outputs import InventoryStudy
from opsrock.inventory.side_by_side import SIDE_BY_SIDE
from opsrock.inventory.stages import Assessment, Route
from opsrock.inventory.study import PLANAR, InventoryDesign, inventory_design
from opsrock.inventory.three_d import THREE_D
from opsrock.solvers.registry import METHODS as SOLVER_INFO
from opsrock.solvers.registry import plan_solver

#: The models a study runs its items in: planar per axis, every item in three dimensions, or both side by side.
MODELS: tuple[str, ...] = ("planar", "3d", "both")


def route_of(design: Any) -> Route:
    """The configuration that runs ``design`` (the module docstring's table).

    Raises
    ------
    InputError
        A design of no configuration.
    """
    if isinstance(design, InventoryDesign):
        if design.side_by_side:
            return SIDE_BY_SIDE
        return THREE_D if SOLVER_INFO[design.solver].plan else PLANAR
    if isinstance(design, ContentsDesign):
        return FEMA_NINE
    if isinstance(design, DirectionalityDesign):
        return BOTH
    raise InputError(f"design must be an InventoryDesign, ContentsDesign or DirectionalityDesign, got "
                     f"{type(design).__name__}", argument="design")


def run_design(design: Any, out_dir: str | Path, options: StudyOptions | None = None) -> InventoryStudy:
    """Run (or resume) ``design`` by the stages of :class:`~opsrock.inventory.stages.Assessment` on its route
    (:func:`route_of`) and write its outputs into ``out_dir``.

    Parameters
    ----------
    design : InventoryDesign, ContentsDesign or DirectionalityDesign
        What to compute (made quick, if wanted, by its module's ``quick``).
    out_dir : str or Path
        Output folder (``report.md``, the tables, ``figures/``, ``pelicun/``); written together, all or nothing.
    options : StudyOptions, optional
        Processes, progress on stderr, whether stored results of other settings are deleted, where the campaigns
        keep their stores, the case budget (s) (:class:`StudyOptions`; default its defaults).

    Returns
    -------
    InventoryStudy
        The paths written, the case counts, the wall times (s) and the route's ``summary``.
    """
    o = options if options is not None else StudyOptions()
    out = Path(out_dir)
    store = Path(o.store_dir) if o.store_dir is not None else out / "campaigns"
    return Assessment(design, route_of(design), out, store, o).run()


def study_design(inventory: str | Path | None = None, motions: str | Path | None = None, *, model: str = "planar",
                 building: Any = None, quick: bool = False, workers: int | None = None, **settings: Any) -> Any:
    """The design :func:`run_study` runs for these arguments (the configuration ``opsrock contents`` picks):

    * neither ``inventory`` nor ``motions``, ``model="planar"``: the FEMA P-58 preset, the nine unanchored items in
      ``building`` beside FEMA's fragilities, its period sweep included unless ``sweep=()``
      (:class:`~opsrock.inventory.fema.design.ContentsDesign`; ``settings``: ``items``, ``variants``,
      ``friction``, ``sweep``, ``levels``, ``n_boot``, ``seed``);
    * either file, or ``model="3d"``: the inventory study (:class:`~opsrock.inventory.study.InventoryDesign`;
      without ``inventory`` FEMA P-58's nine as a shipped inventory, without ``motions`` the floor motions of
      ``building``); ``model="3d"`` every item a box in three dimensions (the registry's solver in plan);
    * ``model="both"``: both models side by side; with neither file the directionality preset (the shipped
      inventories on the shipped building, :class:`~opsrock.inventory.directionality.study.DirectionalityDesign`;
      ``settings`` its fields), with either the inventory study with ``side_by_side``
      (:mod:`opsrock.inventory.side_by_side`).

    Raises
    ------
    InputError
        An unknown ``model``, or a setting the configuration does not take.
    """
    from opsrock.inventory.sources import BuildingSource

    if model not in MODELS:
        raise InputError(f"model must be one of {', '.join(MODELS)}, got {model!r}", argument="model")
    source = building if building is not None else BuildingSource()
    try:
        if model == "both" and inventory is None and motions is None:
            design = DirectionalityDesign(**settings)
            return quick_both(design) if quick else design
        if inventory is None and motions is None and model == "planar":
            fields = {f.name: getattr(source, f.name) for f in dataclasses.fields(source)}
            design = ContentsDesign(**{"sweep": SWEEP_BUILDINGS, **fields, **settings})
            return quick_fema(design) if quick else design
    except TypeError as e:  # a setting the design has no field for
        raise InputError(f"{e}", argument="settings") from None
    if model == "3d":
        settings.setdefault("solver", plan_solver())
    if model == "both":
        settings["side_by_side"] = True
    return inventory_design(inventory, motions, source, settings, quick_run=quick, workers=workers)


def run_study(inventory: str | Path | None = None, motions: str | Path | None = None, out_dir: str | Path = "contents",
              *, model: str = "planar", building: Any = None, quick: bool = False,
              options: StudyOptions | None = None, **settings: Any) -> InventoryStudy:
    """One contents study from Python, as ``opsrock contents`` runs it for the same arguments: each item's
    fragility per floor, the expected numbers damaged, the report and a pelicun folder, in ``out_dir``.

    Parameters
    ----------
    inventory : str, Path or None
        An inventory file (CSV or TOML; m, kg); None: FEMA P-58's nine unanchored items.
    motions : str, Path or None
        A motions manifest (floor accelerations, m/s² or g as it says); None: the floor motions of the shipped
        shear building ``building``.
    out_dir : str or Path
        The output folder (resumable: a second run computes only what is missing).
    model : str
        ``"planar"`` (each item per axis), ``"3d"`` (every item a box in three dimensions) or ``"both"`` (side by
        side); with neither file, ``"planar"`` runs FEMA P-58's preset, as ``opsrock contents`` does
        (:func:`study_design` says which configuration runs for which arguments).
    building : BuildingSource, optional
        The shipped building, its floors and records when ``motions`` is None
        (:class:`opsrock.inventory.sources.BuildingSource`; default its defaults: T1 = 1.0 s, 8 storeys).
    quick : bool
        A quick study (fewer levels, records and resamples).
    options : StudyOptions, optional
        Processes, progress on stderr, whether stored results of other settings are deleted, where the campaigns
        keep their stores, the case budget (s) (:class:`StudyOptions`; default its defaults).
    **settings
        Fields of the configuration's design: :class:`~opsrock.inventory.study.InventoryDesign` (``method``
        ``"ida"`` or ``"cloud"``, ``levels``, ``n_boot``, ``seed``, ``slide_distance`` in m, ``azimuths`` in
        deg, ...), :class:`~opsrock.inventory.fema.design.ContentsDesign` (``items``, ``variants``,
        ``friction``, ``sweep``) or :class:`~opsrock.inventory.directionality.study.DirectionalityDesign`.

    Returns
    -------
    InventoryStudy
        The paths written (``tables``, ``pelicun``, ``report``, ``figures``), the case counts and the wall times (s).

    Examples
    --------
    >>> import opsrock
    >>> from importlib.resources import files
    >>> data = files("opsrock.data")
    >>> study = opsrock.run_study(data / "inventories" / "example.csv",
    ...                           data / "examples" / "floor-motions" / "motions.csv", "my-building",
    ...                           quick=True, options=opsrock.StudyOptions(progress=False))  # doctest: +SKIP
    >>> sorted(study.tables)  # doctest: +SKIP
    ['demands', 'expected', 'fits']

    FEMA P-58's nine in the shipped building (``opsrock contents``), and the same items in three dimensions:

    >>> opsrock.run_study(out_dir="fema-nine", quick=True)  # doctest: +SKIP
    >>> opsrock.run_study(out_dir="fema-nine-3d", model="3d", quick=True)  # doctest: +SKIP
    """
    o = options if options is not None else StudyOptions()
    design = study_design(inventory, motions, model=model, building=building, quick=quick, workers=o.workers,
                          **settings)
    return run_design(design, out_dir, o)


__all__ = ["MODELS", "StudyOptions", "route_of", "run_design", "run_study", "study_design"]
