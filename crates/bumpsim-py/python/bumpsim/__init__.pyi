"""bumpsim: low-speed bumper impact toolkit (Python bindings of the Rust crates).

Units are SI throughout (kg, m, s, N). Arrays in are 1-D ``numpy.float64``
arrays (or sequences of numbers); any other dtype or shape raises
:class:`InputError` naming the argument. Arrays out are ``numpy.float64``,
read-only and made once per object (``.copy()`` for a writable one). Every
object pickles, compares equal to its copy and has a readable repr;
``to_pandas()`` gives tables as pandas objects (pandas is imported only
then). Every number comes from the Rust library; long calls release the GIL.
"""

import pathlib
from os import PathLike
from typing import Any, Callable, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str

StrPath = Union[str, "PathLike[str]"]
FloatArray = npt.NDArray[np.float64]
# float64 at run time (other dtypes raise InputError); typed wide enough for
# numpy expressions, which type as floating[Any]
ArrayLike1D = Union[npt.NDArray[np.floating[Any]], Sequence[float]]
# a car: a Car, or the path of a car file (TOML) or identification result (JSON)
CarLike = Union["Car", str, "PathLike[str]"]
# pandas.DataFrame and pandas.Series: pandas is optional (and ships no
# stubs), so the stubs do not import it
DataFrame = Any
Series = Any
# model orders: a number, a range "1..5" or a list
Dofs = Union[int, str, Sequence[int]]

# The exceptions: one hierarchy on Python's own bases, messages as the CLI's.
#   Error (Exception)
#   ├── InputError (Error, ValueError)           a bad value, array, option or file content
#   ├── FileError (Error, OSError)               a file or folder that cannot be read
#   │   └── MissingFileError (FileError, FileNotFoundError)   it does not exist
#   └── RunError (Error, RuntimeError)           a campaign's controller or scheduler

class Error(Exception):
    """Base class of every bumpsim error; the message is the library's."""

class InputError(Error, ValueError):
    """A value, array or file content the library refuses (a ValueError); the
    message names the parameter, file, line or channel."""

class FileError(Error, OSError):
    """A file or folder that cannot be read (an OSError; errno and filename
    set when known)."""

class MissingFileError(FileError, FileNotFoundError):
    """A file, folder or program that does not exist (a FileNotFoundError)."""

class RunError(Error, RuntimeError):
    """A campaign that cannot go on: another controller holds its lock, or the
    scheduler failed."""

# ---------------------------------------------------------------- models

class Car:
    """An n-DOF chain mass-spring-damper car model, validated by the core.

    ``Car([1.8, 74.8, 1670.0], [6.46e6, 1.97e5], [4.75e5, 5.0e5])``: masses
    (kg, m1 carries the bumper), dampers c1..c(n-1) (N·s/m) and springs
    k1..k(n-1) (N/m). Raises :class:`InputError` naming the bad parameter.
    """

    def __init__(
        self,
        masses: ArrayLike1D,
        dampers: ArrayLike1D,
        springs: ArrayLike1D,
        name: Optional[str] = None,
    ) -> None: ...
    @staticmethod
    def from_file(path: StrPath) -> "Car":
        """Reads a car file (TOML) or an identification result (``identify --json``)."""
    @property
    def name(self) -> Optional[str]: ...
    @property
    def dof(self) -> int:
        """Number of masses."""
    @property
    def masses(self) -> FloatArray:
        """Masses, kg."""
    @property
    def dampers(self) -> FloatArray:
        """Dampers, N·s/m."""
    @property
    def springs(self) -> FloatArray:
        """Springs, N/m."""
    @property
    def total_mass(self) -> float:
        """Total mass, kg."""
    def to_toml(self) -> str:
        """The car file text."""
    def to_pandas(self) -> DataFrame:
        """Index ``parameter`` (m1.., c1.., k1..), columns ``value`` (SI) and ``unit``."""

class Response:
    """A simulation's response, SI: rows are masses (displacement, velocity,
    acceleration) or links (spring and damper forces, positive in
    compression), columns are samples."""

    method: str
    time: FloatArray
    force: FloatArray
    displacement: FloatArray
    velocity: FloatArray
    acceleration: FloatArray
    spring_force: FloatArray
    damper_force: FloatArray
    kinetic_energy: FloatArray
    spring_energy: FloatArray
    dissipated_energy: FloatArray
    work: FloatArray
    impulse: FloatArray
    momentum: FloatArray
    energy_error: float
    """Energy balance error relative to the largest energy term."""
    momentum_error: float
    """Momentum error relative to the impulse."""
    warnings: list[str]
    def to_pandas(self) -> DataFrame:
        """As ``bumpsim simulate -o`` writes it: index ``time [s]``, columns
        ``force [N]``, ``x1 [m]``, ..., ``work [J]``; attrs: method,
        energy_error, momentum_error, warnings."""

def simulate(
    car: CarLike,
    time: ArrayLike1D,
    force: ArrayLike1D,
    method: str = "zoh",
    initial_velocity: float = 0.0,
    substeps: Union[int, str, None] = None,
) -> Response:
    """Simulates ``car`` under ``force`` (N, on m1) sampled at ``time`` (s;
    uniform: within 1e-6 of an interval of the mean grid), every mass starting
    at ``initial_velocity`` (m/s); ``method`` is ``zoh`` (exact, default),
    ``foh`` or ``taylor1`` (with ``substeps`` per sample, a number or
    ``"auto"``). As ``bumpsim simulate``."""

# ---------------------------------------------------------------- signals

class Entry:
    """A channel as a test lists it, before its samples are read."""

    number: int
    code: str
    name: str
    unit: str
    """The unit as the file writes it."""
    invalid: Optional[str]
    """None when usable, else the lab's reason for marking it invalid."""
    present: bool
    absence: Optional[str]
    metadata: dict[str, str]

class Channel:
    """A loaded channel: code, name, SI unit, uniform time base, samples.
    The processing methods return a new channel (its code follows the
    processing, e.g. the filter class letter)."""

    code: str
    name: str
    unit: str
    """SI unit of ``data``."""
    source_unit: str
    metadata: dict[str, str]
    start: float
    step: float
    time: FloatArray
    data: FloatArray
    def cfc(self, cls: float, standard: str = "sae-j211") -> "Channel":
        """CFC filter (SAE J211-1, or ``iso-6487``), as ``signal export --cfc``."""
    def bias(self) -> "Channel":
        """Removes the mean of the samples before t = 0."""
    def scale(self, factor: float) -> "Channel": ...
    def trim(self, t0: float, t1: float) -> "Channel":
        """Keeps the samples in [t0, t1] s."""
    def resample(self, step: float) -> "Channel":
        """Resamples to the interval ``step`` s."""
    def moving_average(self, points: int) -> "Channel": ...
    def integrate(self, initial: float = 0.0) -> "Channel":
        """Integrates; the result equals ``initial`` (SI) at t = 0."""
    def to_pandas(self) -> Series:
        """The samples named ``CODE [unit]``, indexed by ``time [s]``."""
    def __len__(self) -> int: ...

class Test:
    """A crash test (ISO-MME, NHTSA EV5 or CSV): metadata, channel list and
    channels loaded on demand."""

    path: pathlib.Path
    format: str
    title: str
    metadata: dict[str, str]
    speed: Optional[float]
    """Impact speed, m/s, when the file states it."""
    mass: Optional[float]
    """Test mass, kg, when the file states it."""
    entries: list[Entry]
    channels: list[Channel]
    """Every usable channel (valid, samples present)."""
    def select(self, selector: str) -> list[Channel]:
        """Channels by number, code (``?``/``*`` wildcards) or name substring."""
    def channel(self, number: int) -> Channel:
        """One channel by number, even if marked invalid."""
    def to_pandas(self) -> DataFrame:
        """The channel list: index ``number``, columns code, name, unit,
        invalid, present, absence; attrs: path, format, title, speed, mass."""

def read_test(path: StrPath) -> Test:
    """Opens an ISO-MME folder, ``.mme`` or ``.zip``, an NHTSA ``.EV5`` file or a CSV file."""

def contact_window(force: ArrayLike1D, rise: float = 0.05, fall: float = 0.02) -> tuple[int, int]:
    """First and last sample (inclusive) of the contact: |F| rises to ``rise``
    and last stays at ``fall`` of its peak."""

def cfc(x: ArrayLike1D, fs: float, cls: float, standard: str = "sae-j211") -> FloatArray:
    """Filters ``x`` sampled at ``fs`` Hz with a CFC filter of class ``cls``, zero phase."""

def iso18571(reference: ArrayLike1D, candidate: ArrayLike1D, step: float) -> dict[str, float]:
    """ISO/TS 18571 rating of ``candidate`` against ``reference`` (same
    instants, every ``step`` s): overall, corridor, phase, magnitude, slope."""

# ---------------------------------------------------------------- identification

class Prediction:
    """A load case simulated with an identified model next to its measurement."""

    name: str
    sse: float
    fit_percent: float
    window: tuple[float, float]
    time: FloatArray
    measured: FloatArray
    simulated: FloatArray
    rating: Optional[dict[str, float]]
    """ISO/TS 18571 rating in the window: overall, corridor, phase,
    magnitude, slope (None when the window cannot be rated)."""
    def to_pandas(self) -> DataFrame:
        """Index ``time [s]``, columns ``measured [m]``, ``simulated [m]``."""

class Identification:
    """An identified model with the fields of ``bumpsim identify --json``."""

    dof: int
    car: Car
    masses: FloatArray
    dampers: FloatArray
    springs: FloatArray
    parameters: list[dict[str, Any]]
    """name, value, unit, standard_error, ci95 per parameter (thesis order)."""
    standard_errors: list[Optional[float]]
    uncertainty: dict[str, Any]
    objective: float
    """The objective at the optimum, in ``objective_unit``: Σ (x − x̂)² over
    all cases in m² for the thesis's displacement objective, else the
    compared domain's unit squared, or dimensionless when weighted by the
    noise."""
    objective_unit: str
    """``m²``, ``(m/s)²``, ``(m/s²)²``, ``dimensionless`` or
    ``dimensionless + (m/s)²`` (some cases weighted), as the CLI prints it."""
    fit_percent: float
    aic: float
    bic: float
    cases: list[dict[str, Any]]
    """Per-case fit: name, sse (m²), fit_percent, samples, rating, window (s)."""
    starts: dict[str, int | float]
    """Start counts; ``inflation`` (κ, the residuals' variance inflation the
    ``reached_correlated`` and ``explored_correlated`` counts use) a float."""
    start: list[float]
    compared: dict[str, Any] | None
    priors: list[dict[str, Any]]
    """The stated priors: name, centre (SI), spread (sd of ln θ), source,
    estimate (SI), z (how far the data moved it, prior sd); empty without."""
    prior_noise: Optional[float]
    residuals: int
    iterations: int
    stop: Any
    """Why the best start stopped."""
    run_time: float
    """Wall-clock time, s."""
    warnings: list[str]
    reduction: Optional[dict[str, Any]]
    """The simpler model that fits as well (an undetermined spring, or a link
    the data do not need by the F-test): parameter, statement, model (masses,
    dampers, springs; SI), objective (m²), relative_objective, p_value; None
    otherwise."""
    notes: list[str]
    effective_samples: dict[str, Any]
    """The effective sample size of the residuals at the optimum."""
    cross_validation: Optional[dict[str, Any]]
    """Leave-one-load-case-out cross-validation (error m², folds) when a DOF
    table ran it."""
    def to_json(self) -> str:
        """The result as ``bumpsim identify --json`` writes it."""
    def to_pandas(self) -> DataFrame:
        """The parameters: index ``parameter``, columns value, standard_error,
        ci95_low, ci95_high (SI, in the row's ``unit``), unit, determined,
        at_bound, fixed; attrs: dof, the objective keyed by its unit
        (``objective [m^2]``, ``objective [(m/s)^2]``, ``objective
        [(m/s^2)^2]``, ``objective [dimensionless]``), ``fit [%]``,
        warnings."""
    def cases_to_pandas(self) -> DataFrame:
        """The per-case fits: index ``case``, columns ``sse [m^2]`` (the
        displacement's, whatever the objective's domain, as the CLI prints
        it), ``fit [%]``, samples and the ISO/TS 18571 ratings."""
    def predict(self) -> list[Prediction]:
        """Simulates the study's load cases with the identified model."""
    def report(self) -> tuple[str, dict[str, str]]:
        """The HTML report of ``bumpsim identify --report`` (with the ±3 %
        sensitivity): the page and its SVG figures, file name → text."""
    def posterior(
        self, seed: Optional[int] = None, steps: Optional[int] = None, walkers: Optional[int] = None
    ) -> "Posterior":
        """Samples the posterior of the parameters (the ensemble sampler with
        this identification's noise model, log-uniform prior within its
        bounds), seeded (default: the identification's seed); ``steps`` (a
        quarter burnt, default 4000) and ``walkers`` (default 32 at least)."""

class Posterior:
    """The posterior of an identified model's parameters (thesis order, SI):
    means, medians, deviations, equal-tailed 90 % and 95 % intervals, the
    sampler's diagnostics and the kept draws."""

    names: list[str]
    units: list[str]
    mean: FloatArray
    median: FloatArray
    sd: FloatArray
    ci90: list[Optional[tuple[float, float]]]
    """5 % and 95 % quantiles; None for a fixed parameter."""
    ci95: list[Optional[tuple[float, float]]]
    fixed: list[bool]
    noise: dict[str, float]
    ensemble: dict[str, int]
    """walkers, steps, burn, seed."""
    diagnostics: dict[str, Any]
    """autocorrelation_time, time_reliable, effective_draws, r_hat (free
    parameters), acceptance, converged, warnings."""
    converged: bool
    warnings: list[str]
    samples: FloatArray
    """The kept draws: one row per draw, one column per parameter (read-only)."""
    def to_text(self) -> str:
        """Each parameter's median, 90 % and 95 % intervals beside its local 95 %, the
        diagnostics and warnings."""
    def to_json(self) -> str:
        """As ``bumpsim identify --posterior --json`` writes its ``posterior``."""
    def to_pandas(self) -> DataFrame:
        """The draws: columns ``m1 [kg]``, ..., ``k1 [N/m]``; attrs: ensemble,
        noise, converged, warnings."""
    def summary_to_pandas(self) -> DataFrame:
        """Index ``parameter``; mean, median, sd, ci90_low, ci90_high,
        ci95_low, ci95_high, local_ci95_low, local_ci95_high (SI, in the row's
        ``unit``), unit, fixed."""

def identify(
    study: StrPath,
    dof: Optional[Union[int, str]] = None,
    starts: Optional[int] = None,
    seed: Optional[int] = None,
    progress: Optional[Callable[[], Any]] = None,
) -> Union[Identification, "StudyIdentification"]:
    """Identifies the study file as ``bumpsim identify STUDY --dof N --starts S
    --seed X`` does, by the model its ``kind`` declares: a chain study's one
    MSD model from its load cases (an :class:`Identification`); a links or
    planar study through the same engine request as the CLI (a
    :class:`StudyIdentification`). ``progress`` is called once per finished
    start."""

class StudyIdentification:
    """A links or planar study identified by the engine, as ``bumpsim
    identify STUDY`` identifies it: every field of its ``--json`` document is
    an attribute (a links study's ``parameters`` with units and 95 %
    intervals, ``fits`` and ``force_fits`` per test in %, ``linear``,
    ``verdict`` of linear vs nonlinear links, ``plastic_sets`` with 95 %
    intervals, ``forward`` runs into a rigid wall; SI)."""

    kind: str
    """The study's model kind: ``links`` or ``planar``."""
    study: pathlib.Path
    document: dict[str, Any]
    """The whole ``identify --json`` document."""
    warnings: list[str]
    car_toml: Optional[str]
    """The identified car file, as ``identify --car`` writes it."""
    def summary(self) -> str:
        """What ``bumpsim identify STUDY`` prints."""
    def to_json(self) -> str:
        """The document as ``bumpsim identify --json`` writes it."""
    def write_car(self, path: StrPath) -> None:
        """Writes the identified car file as ``identify --car`` does: whole (a
        temporary file renamed), never onto the study or a file it names."""
    def to_pandas(self, table: str) -> DataFrame:
        """A list of the document (``parameters``, ``plastic_sets``,
        ``forward``, ``fits``, ...) as a table: a row per entry, indexed by
        ``case`` and ``name`` where every entry has them; an interval becomes
        ``ci95_low`` and ``ci95_high``; a ``[name, value]`` pair a row
        ``name``, column the field (SI; units in a ``unit`` column)."""
    def __getattr__(self, name: str) -> Any:
        """A field of the ``identify --json`` document."""

class DofTable:
    """Models of several orders from one study (the thesis's table 1), each
    continued from the last, as ``bumpsim identify STUDY --dof 1..5``."""

    results: list[Identification]
    failed: dict[int, str]
    """The orders that failed: DOF → reason."""
    notes: list[str]
    recommended: Optional[int]
    def to_text(self) -> str:
        """The table as ``bumpsim identify --dof 1..5`` prints it."""
    def to_json(self) -> str:
        """The table as ``bumpsim identify --dof 1..5 --json`` writes it."""
    def to_pandas(self) -> DataFrame:
        """Index ``dof``, columns ``objective [UNIT]`` (keyed as in
        ``Identification.to_pandas``), ``fit [%]``, ``aic [-]``,
        ``bic [-]``, parameters, ``run_time [s]``; attrs: recommended, failed."""
    def __len__(self) -> int: ...

def dof_table(
    study: StrPath,
    dofs: Optional[Dofs] = None,
    starts: Optional[int] = None,
    seed: Optional[int] = None,
    progress: Optional[Callable[[], Any]] = None,
) -> DofTable:
    """The DOF table of the study file over ``dofs`` (a number, a range
    ``"1..5"`` or a list; default the study's); an order that fails is listed
    with its reason and the others go on."""

class LoadCase:
    """A load case from numpy arrays: force on m1 (N) and the measured
    displacement (m) of mass ``output_dof`` (1 = m1) at uniform ``time`` (s);
    ``window`` (t0, t1) s is the fit window (default: every sample); one
    reaching past the record (beyond half a sample) is refused with
    ``InputError``, as the CLI refuses a study's, not cut to it."""

    name: str
    output_dof: int
    initial_velocity: float
    time: FloatArray
    force: FloatArray
    displacement: FloatArray
    window: tuple[float, float]
    def to_pandas(self) -> DataFrame:
        """Index ``time [s]``, columns ``force [N]`` and ``displacement [m]``."""
    def __init__(
        self,
        name: str,
        time: ArrayLike1D,
        force: ArrayLike1D,
        displacement: ArrayLike1D,
        output_dof: int = 1,
        initial_velocity: float = 0.0,
        window: Optional[tuple[float, float]] = None,
    ) -> None: ...

def identify_cases(
    cases: Sequence[LoadCase],
    dof: int,
    starts: Optional[int] = None,
    seed: Optional[int] = None,
    progress: Optional[Callable[[], Any]] = None,
) -> Identification:
    """Identifies one ``dof``-mass model from load cases built in Python
    (library defaults: every parameter ≥ 1 in SI)."""

# ---------------------------------------------------------------- impact

class Bumper:
    """A bumper characteristic."""

    @staticmethod
    def from_file(path: StrPath) -> "Bumper": ...
    @property
    def unloading(self) -> float:
        """The unloading slope, N/m."""
    def to_pandas(self) -> DataFrame:
        """The loading curve: index ``compression [m]``, column ``force [N]``."""

class Impact:
    """An impact's result, SI, with the fields of ``bumpsim impact --json``."""

    scenario: dict[str, Any]
    peak_force: float
    max_compression: float
    remaining_compression: float
    contact_time: float
    absorbed_energy: float
    energy: dict[str, float]
    step: float
    bodies: list[str]
    time: FloatArray
    force: FloatArray
    compression: FloatArray
    displacements: FloatArray
    velocities: FloatArray
    warnings: list[str]
    prediction: Optional[dict[str, Any]]
    """The JSON's ``prediction`` (each output's nominal value and spread, each
    history's band); None without ``uncertainty``."""
    sensitivity: Optional[dict[str, Any]]
    """The JSON's ``sensitivity`` (Sobol first-order and total indices); None without ``sobol``."""
    bands: Optional[dict[str, dict[str, FloatArray]]]
    """History name → arrays ``time`` [s], ``nominal``, ``low``, ``median``, ``high``."""
    def prediction_to_pandas(self) -> Optional[DataFrame]:
        """The spreads: index ``output``; ``unit``, ``nominal``, ``median``, ``low``,
        ``high``, ``mean``, ``sd``; attrs: sampling, failed. None without ``uncertainty``."""
    def summary(self) -> str: ...
    def to_json(self) -> str: ...
    def to_pandas(self) -> DataFrame:
        """As ``bumpsim impact --csv`` writes it: index ``time [s]``, columns
        ``force [N]``, ``compression [m]``, ``x BODY [m]``, ``v BODY [m/s]``."""

def presets() -> list[dict[str, Any]]:
    """The one table of tests, as `bumpsim impact --case list` (name, protocol,
    speed_kmh, description, source, uncertain, dropped_in_1d)."""

def impact(
    car: CarLike,
    bumper: Union[Bumper, StrPath],
    case: Optional[str] = None,
    pendulum: Optional[float] = None,
    barrier: bool = False,
    speed: Optional[float] = None,
    *,
    uncertainty: Optional[StrPath] = None,
    samples: int = 1000,
    seed: int = 1,
    level: float = 0.9,
    sobol: bool = False,
    sobol_base: int = 256,
) -> Impact:
    """A preset ``case``, or a ``pendulum`` (kg) or rigid ``barrier`` at ``speed`` (m/s).

    With ``uncertainty`` (an identification's JSON or a TOML of
    ``[uncertainty]`` spreads and/or ``[ranges]``, docs/uncertainty.md), also
    the prediction over ``samples`` (10..100000) seeded draws of the car at
    ``level``, and with ``sobol`` the Sobol indices (``sobol_base`` 16..65536
    base samples), as ``bumpsim impact --uncertainty``: ``Impact.prediction``,
    ``.sensitivity``, ``.bands``."""

def mass_reduction(
    m1: float, m2: float, k: float, bumper: Bumper, speed: float, criterion: str = "remaining"
) -> dict[str, Any]:
    """Paper A's equivalent single mass of a 2-DOF car into a rigid barrier."""

# ---------------------------------------------------------------- planar car

class PlanarCar:
    """A planar car (yaw, left/right chains, segmented bumper, tyres; docs/planar.md)."""

    name: Optional[str]
    path: pathlib.Path
    """The file it was read from."""
    @staticmethod
    def from_file(path: StrPath) -> "PlanarCar": ...
    def to_toml(self) -> str:
        """The car as a planar car file (SI lengths)."""

class PlanarImpact:
    """A planar impact's result with the fields of ``bumpsim planar --json``."""

    result: dict[str, Any]
    warnings: list[str]
    prediction: Optional[dict[str, Any]]
    """The JSON's ``prediction`` (each output's nominal value and spread, each
    history's band); None without ``uncertainty``."""
    sensitivity: Optional[dict[str, Any]]
    """The JSON's ``sensitivity`` (Sobol first-order and total indices); None without ``sobol``."""
    bands: Optional[dict[str, dict[str, FloatArray]]]
    """History name → arrays ``time`` [s], ``nominal``, ``low``, ``median``, ``high``."""
    def prediction_to_pandas(self) -> Optional[DataFrame]:
        """The spreads: index ``output``; ``unit``, ``nominal``, ``median``, ``low``,
        ``high``, ``mean``, ``sd``; attrs: sampling, failed. None without ``uncertainty``."""
    def summary(self) -> str:
        """What ``bumpsim planar`` prints: the heading (car and striker), the
        tyres a preset sets, the summary and, with ``uncertainty``, the
        prediction's lines."""
    def to_json(self) -> str: ...
    def to_pandas(self) -> DataFrame:
        """As ``bumpsim planar --csv`` writes it: index ``time [s]``."""

def planar_impact(
    car: PlanarCar,
    case: Optional[str] = None,
    angle: Optional[float] = None,
    overlap: Optional[float] = None,
    side: str = "left",
    pole: Optional[float] = None,
    pole_offset: float = 0.0,
    pendulum: Optional[float] = None,
    speed: Optional[float] = None,
    *,
    uncertainty: Optional[StrPath] = None,
    samples: int = 1000,
    seed: int = 1,
    level: float = 0.9,
    sobol: bool = False,
    sobol_base: int = 256,
) -> PlanarImpact:
    """A preset ``case``; or a barrier (or ``pendulum``, kg) at ``angle`` degrees
    with ``overlap`` % from ``side``; or a pole of diameter ``pole`` m at
    ``pole_offset`` m; ``speed`` in m/s. ``uncertainty`` and the rest: as
    :func:`impact` (``bumpsim planar --uncertainty``)."""

# ---------------------------------------------------------------- verdicts

# a planar car with its [damageability]: a PlanarCar or the path of its file
PlanarCarLike = Union["PlanarCar", str, "PathLike[str]"]

class BumperTarget:
    """The region of bumper characteristics that passes every criterion
    (``bumpsim verdict --target``): per whole-bumper initial stiffness the
    passing force levels and the criterion binding at each boundary."""

    origin: tuple[float, float]
    """The car's own bumper: initial stiffness (N/m), force level (N)."""
    tabulated: bool
    margin: float
    impacts: int
    seconds: float
    rows: list[dict[str, Any]]
    def contains(self, stiffness: float, force: float) -> bool:
        """Whether a whole-bumper stiffness (N/m) and force level (N) lie in the region."""
    def to_text(self) -> str: ...
    def to_json(self) -> str:
        """The JSON's ``target``."""
    def to_pandas(self) -> DataFrame:
        """Index ``stiffness [N/m]``; ``force low [N]``, ``binding low``,
        ``force high [N]``, ``binding high``, ``stroke [m]``, ``failing``."""
    def corridor_to_pandas(self) -> DataFrame:
        """Index ``deflection [m]``; ``lower [N]``, ``upper [N]``."""

class Verdict:
    """The verdict of a car in a set of tests (``bumpsim verdict``)."""

    car: str
    margin: float
    passed: bool
    failures: list[tuple[str, str]]
    """The failing criteria: (test, criterion)."""
    tests: list[dict[str, Any]]
    """The JSON's ``verdict.tests``."""
    target: Optional[BumperTarget]
    def to_text(self) -> str:
        """The tables ``bumpsim verdict`` prints."""
    def to_json(self) -> str:
        """As ``bumpsim verdict --json`` writes it."""
    def to_pandas(self) -> DataFrame:
        """Index (``test``, ``criterion``); value, limit, margin (SI, in the
        row's ``unit``), ``ratio [1]``, upper, outcome, pass, detail."""
    def tests_to_pandas(self) -> DataFrame:
        """Index ``test``: end, striker, passed, binding, pulse metrics and
        energies with units, skipped."""

def verdict(
    car: Union[PlanarCarLike, Sequence[PlanarCarLike]],
    protocol: Optional[Union[str, Sequence[str]]] = None,
    margin: float = 0.0,
    bumper: Optional[Union["Bumper", StrPath]] = None,
    target: bool = False,
    sequence: bool = False,
) -> Verdict:
    """As ``bumpsim verdict --car CAR --protocol P --margin M [--target] [--sequence]``:
    one planar car file with a ``[damageability]`` table per end; protocols
    or tests by name (comma-separated, a list, default ``"all"``); ``bumper``
    replaces the car's, shared equally by its segments; ``sequence`` runs the
    tests in order on one car per end, each from the damage the earlier ones
    left (the JSON's ``inherited``)."""

def protocols() -> str:
    """The protocols and their tests with sources and uncertainties (``bumpsim verdict --list``)."""

# ---------------------------------------------------------------- DOE

class Design:
    names: list[str]
    order: list[int]
    coded: FloatArray
    """Runs (in run order) × factors, coded levels."""
    physical: FloatArray
    resolution: Optional[int]
    def to_csv(self) -> str:
        """The table ``bumpsim doe design -o`` writes."""
    def to_pandas(self) -> DataFrame:
        """That table: index ``run``, columns ``standard order``, the factors'
        levels and ``NAME (coded)``."""

def doe_design(
    kind: str,
    factors: Sequence[str],
    generators: Sequence[str] = (),
    centre: int = 0,
    runs: int = 20,
    seed: int = 1,
    randomise: bool = False,
) -> Design:
    """``kind``: full, fractional, ccf, ccc, lhs, uniform; ``factors`` as ``"NAME:LOW:HIGH"``."""

def doe_stiffness(
    displacement: ArrayLike1D, force: ArrayLike1D, range: Optional[tuple[float, float]] = None
) -> dict[str, Any]:
    """Slope (N/m), intercept, range, points, residual_rms, r2 of the line through
    the curve over ``range`` (m; default 10–90 % of the peak force); ``r2`` is
    None when the force does not vary (R² undefined)."""

class DoeModel:
    @staticmethod
    def from_file(path: StrPath) -> "DoeModel": ...
    def to_json(self) -> str: ...
    def as_dict(self) -> dict[str, Any]: ...
    def predict(self, at: Sequence[tuple[str, float]]) -> dict[str, Any]:
        """Values with 95 % confidence and prediction intervals at physical factor values."""
    def to_pandas(self) -> DataFrame:
        """Coefficients in coded units: index (``response``, ``term``), columns
        coefficient, std_error, ci95_low, ci95_high, unit."""

def doe_fit(
    data: StrPath,
    factors: Sequence[str],
    responses: Sequence[str],
    low: Sequence[float] = (),
    high: Sequence[float] = (),
    interactions: bool = False,
    squares: bool = False,
    se: Sequence[str] = (),
) -> DoeModel:
    """Regression of data-file responses on factors in coded units, as ``bumpsim doe fit``;
    ``se`` as ``--se``: ``"RESPONSE=COLUMN"`` or ``"RESPONSE"`` (column ``RESPONSE.se``),
    those responses weighted by their identification's standard errors (REML)."""

# ---------------------------------------------------------------- export

def lsdyna_deck(
    car: CarLike,
    units: str = "si",
    axis: str = "+x",
    origin: Sequence[float] = (0.0, 0.0, 0.0),
    spacing: float = 0.1,
    id_offset: int = 0,
    attach: Sequence[int] = (),
    initial_velocity: Optional[float] = None,
    title: Optional[str] = None,
    time: Optional[ArrayLike1D] = None,
    force: Optional[ArrayLike1D] = None,
    output_interval: Optional[float] = None,
    standalone: bool = False,
) -> str:
    """The LS-DYNA keyword include (units si, mm-s-t or mm-ms-kg); with
    ``time`` and ``force`` a load curve on m1, with ``output_interval`` (s)
    history outputs, with ``standalone`` a complete run."""

def critical_time_step(car: CarLike) -> float:
    """The critical explicit time step of the car alone, s."""

def calculix(
    car: CarLike,
    time: Optional[ArrayLike1D] = None,
    force: Optional[ArrayLike1D] = None,
    units: str = "si",
    axis: str = "+x",
    origin: Sequence[float] = (0.0, 0.0, 0.0),
    spacing: float = 0.1,
    increment: Optional[float] = None,
    output_every: int = 1,
    initial_velocity: Optional[float] = None,
    title: Optional[str] = None,
    id_offset: int = 0,
    prefix: str = "BUMPSIM_",
    attach: Sequence[int] = (),
) -> str:
    """The CalculiX/Abaqus deck; with time and force a transient analysis;
    ids offset by ``id_offset`` and set names prefixed with ``prefix``;
    ``attach`` node ids follow m1 along the axis (``*EQUATION``)."""

# ---------------------------------------------------------------- pipelines

class PipelineRun:
    """The signals of a pipeline run (``bumpsim signal process``)."""

    signals: list[Channel]
    raw: list[Channel]
    warnings: list[str]
    balance: Optional[dict[str, Any]]
    """window (s), mass (kg), impulse and momentum_change (N·s), relative_difference."""
    def to_pandas(self) -> DataFrame:
        """As ``bumpsim signal process -o`` writes it: index ``time [s]``, a
        column ``CODE [unit]`` per signal."""

def run_pipeline(path: StrPath) -> PipelineRun:
    """Runs a processing pipeline file (TOML; docs/signals.md)."""

# ---------------------------------------------------------------- campaigns

class CampaignStatus:
    """A campaign's state, as ``bumpsim campaign status --json``."""

    campaign: str
    points: int
    counts: dict[str, int]
    updated: str
    controller: Optional[dict[str, Any]]
    runs: list[dict[str, Any]]
    def text(self) -> str:
        """As ``bumpsim campaign status`` prints it."""
    def to_json(self) -> str: ...
    def to_pandas(self) -> DataFrame:
        """Every point's record, index ``run``."""

class Collected:
    """What ``Campaign.collect`` wrote: the table (``results/table.csv``, the
    CLI's byte for byte), the points left out and the regression."""

    rows: int
    missing: list[tuple[int, str]]
    fit_text: str
    fit_command: str
    table: str
    def to_pandas(self) -> DataFrame:
        """The table: index ``run``, columns ``NAME [unit]`` and ``NAME (coded)``."""

class Campaign:
    """A campaign folder (docs/campaign.md), driven as ``bumpsim campaign``."""

    def __init__(self, folder: StrPath) -> None: ...
    @staticmethod
    def init(spec: StrPath, folder: Optional[StrPath] = None) -> "Campaign":
        """``bumpsim campaign init SPEC -o FOLDER``."""
    @property
    def folder(self) -> pathlib.Path: ...
    def run(
        self, executor: Optional[str] = None, slots: Optional[int] = None, retry_failed: bool = False
    ) -> dict[str, Any]:
        """``bumpsim campaign run``: done, failed [(run, reason)], submitted."""
    def status(self) -> CampaignStatus: ...
    def collect(self) -> Collected:
        """``bumpsim campaign collect``."""
    def abort(self) -> int:
        """``bumpsim campaign abort``: the number of tasks cancelled."""
    def repair(self) -> dict[str, Any]:
        """``bumpsim campaign repair``."""
