"""Type stubs of the compiled part of ``ehl`` (SI units throughout: m, Pa, N, s, Pa s,
kg/m^3, rad)."""

import os
import pathlib
from typing import Any, Callable, Dict, List, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

F64 = npt.NDArray[np.float64]

class Case:
    """A validated case: a case file (TOML, the format of docs/case-file.md) and the overrides
    applied to it. Every constructor and ``set`` validates; errors are ``ehl.CaseError`` with
    ``.file``, ``.key`` and ``.reason``."""

    @staticmethod
    def from_file(path: Union[str, "os.PathLike[str]"]) -> "Case":
        """Reads a case file, as ``ehl run CASE.toml`` does."""
    @staticmethod
    def from_toml(text: str, file: str = "<string>") -> "Case":
        """A case from TOML text; ``file`` names it in errors and is the folder a height map's
        relative path is read from."""
    @staticmethod
    def from_dict(d: Dict[str, Any], file: str = "<dict>") -> "Case":
        """A case from a dict with the case file's structure: nested dicts for tables, a list
        of dicts for ``features``; a value None leaves the key out."""
    def set(self, key: str, value: Any) -> None:
        """Overrides a key by its dotted path, as ``ehl run --set KEY=VALUE``:
        ``set("load.force", 5000)`` (N), ``set("features[0].depth", 1e-7)`` (m),
        ``set("body1.profile", {"kind": "crowned", "crown_radius": 0.5})``. Validates again;
        on a ``CaseError`` (naming the key) the case is unchanged."""
    def get(self, key: str) -> Any:
        """The value of a dotted key as the file or ``set`` gives it (not defaults)."""
    def to_dict(self) -> Dict[str, Any]:
        """The case file's keys with the overrides applied (no defaults filled in)."""
    def to_toml(self) -> str:
        """The case as TOML text, the overrides applied (``ehl run`` reads it)."""
    def check(self) -> Dict[str, Any]:
        """The derived quantities of ``ehl check``: ``reduced_modulus_pa`` (E'),
        ``reduced_radius_m`` (R), ``hertz_half_width_m`` (b), ``hertz_pressure_pa`` (p_h),
        ``load_n``, ``load_per_length_n_m`` (w'), ``W``, ``U``, ``G``, ``moes_M``,
        ``moes_L``, ``spike_pressure_pa``, ``spike_position_m``, ``film_estimates`` (list of
        dicts: ``formula``, ``central_film_m``, ``min_film_m``, ``fitted_with``,
        ``case_uses_same_laws``), the grid (``nx``, ``ny``, ``dx_m``, ``dy_m``,
        ``cells_across_2b``, ``cells_across_y``), ``memory_estimate_bytes`` and
        ``memory_limit_bytes``, for a ``[stress]`` case ``stress`` (``bodies``, ``layers``,
        ``first_depth_m``, ``depth_m``, ``depth_over_b``, ``window_m``, ``window_layers``,
        ``passage_bytes``, ``fatigue``: ``criterion``, ``stress_exponent``,
        ``depth_exponent``, ``weibull_slope``, ``dang_van_alpha``, ``dang_van_beta_pa``) and, for a
        transient case, ``transient`` (``steps``, ``dt_s``, ``x_p_from_m``, ``x_p_to_m``,
        ``u1_m_s``, ``u2_m_s``, ``feature_cells_per_step``, ``steps_for_one_cell``: the
        ``motion.travel.steps`` for one cell a step where the case's move features[0] by more
        than 2, ...), for a thermal case ``thermal``
        (``inlet_temperature_k``, ``viscosity_beta_1_k``, ``thermal_loading_L`` =
        eta0 beta u_e^2 / k_f, ``murch_wilson_film_ratio`` and ``gupta_film_ratio``
        (h_thermal / h_isothermal of the classical fits), ``peclet_1``, ``peclet_2``,
        ``points_across_film``, ``above_converged_loading``: L above the loading below which
        every measured case converged). What does not apply is None."""
    def copy(self) -> "Case": ...
    def __copy__(self) -> "Case": ...
    def __deepcopy__(self, memo: Any) -> "Case": ...
    def __reduce__(self) -> Tuple[Any, Tuple[str, str, List[str]]]:
        """Pickling (process pools): the file's text, its name and the overrides; unpickling
        validates them again."""
    @property
    def file(self) -> str:
        """The case file (made absolute by ``from_file``), or the name given to ``from_toml`` /
        ``from_dict``."""
    @property
    def title(self) -> str: ...
    @property
    def kind(self) -> str:
        """"dry" or "ehl"."""
    @property
    def transient(self) -> bool:
        """True when ``motion.travel`` makes the run transient."""
    @property
    def overrides(self) -> List[str]:
        """The overrides applied, as ``--set`` arguments."""

class Solution:
    """A solved case. The arrays are read-only NumPy views (no copy) of shape (ny, nx), row
    ``j`` along y, column ``i`` along x (an infinite line contact: ny = 1)."""

    @property
    def summary(self) -> Dict[str, Any]:
        """The document ``summary.json`` of ``ehl run``: ``converged``, ``termination``,
        ``iterations``, ``max_pressure_pa``, ``central_film_m``, ``min_film_m``,
        ``friction_coefficient``, ... (SI), ``grid_m`` and ``case`` (the resolved case)."""
    @property
    def converged(self) -> bool: ...
    @property
    def case(self) -> Case: ...
    @property
    def x(self) -> F64:
        """Cell centres along x (m), shape (nx,)."""
    @property
    def y(self) -> F64:
        """Cell centres along y (m), shape (ny,)."""
    @property
    def pressure(self) -> F64:
        """Pressure (Pa), (ny, nx)."""
    @property
    def film(self) -> Optional[F64]:
        """Film thickness (m), (ny, nx); dry: the loaded gap; inf where there is no material."""
    @property
    def deformation(self) -> F64:
        """Combined elastic deflection of both surfaces (m), (ny, nx)."""
    @property
    def viscosity(self) -> Optional[F64]:
        """Viscosity (Pa s), (ny, nx); None for a dry contact."""
    @property
    def density(self) -> Optional[F64]:
        """Density (kg/m^3), (ny, nx); None for a dry contact."""
    @property
    def temperature(self) -> Optional[Dict[str, Any]]:
        """Thermal runs (``[thermal]``): temperatures in K, ``mid_film``, ``max_film``,
        ``surface_1``, ``surface_2`` as read-only (ny, nx) views (NaN where the film was not
        solved), ``film_section`` (nz, nx, K) and ``section_z`` (nz, nx, m) across the film along
        the centre grid line at ``section_y`` (m), and ``inlet`` (K); None when isothermal."""
    @property
    def stress(self) -> Optional[Dict[str, Any]]:
        """``[stress]`` runs: what ``stress.npz`` holds: ``x`` (nx), ``y`` (ny), ``z`` (nz) in m,
        and for each computed body k ``sxx_k``, ``syy_k``, ``szz_k``, ``syz_k``, ``sxz_k``,
        ``sxy_k``, ``von_mises_k``, ``tresca_k`` in Pa (float32, (nz, ny, nx), copies; body
        frame, z depth, tension positive), ``x_p_m`` (m: the kept frame of a transient run,
        else None) and ``with_traction``; None without ``[stress]``."""
    @property
    def timeline(self) -> Optional[Dict[str, npt.NDArray[Any]]]:
        """Transient runs: the columns of ``timeline.csv`` (``step``, ``time_s``, ``x_p_m``,
        ``max_pressure_pa``, ``min_film_m``, ``central_film_m``, ``friction_coefficient``
        (NaN where not computed), ``converged``, ...; thermal runs add
        ``max_film_temperature_k``, ``max_surface_temperature_1_k``,
        ``max_surface_temperature_2_k`` (K), ``heat_generated_w``, ``heat_stored_w`` (W),
        ``energy_balance_error`` and ``thermal_passes``), one entry per step; else None."""
    @property
    def frames(self) -> Optional[List[Dict[str, Any]]]:
        """Transient runs: the kept steps, dicts with ``step``, ``time_s``, ``x_p_m`` (m),
        ``pressure`` (Pa) and ``film`` (m) as (ny, nx) views; else None."""
    @property
    def snapshots(self) -> Optional[List[Dict[str, Any]]]:
        """Transient runs: the fields at ``output.snapshots`` (``x_p_m``, ``step``,
        ``pressure``, ``film``, ``deformation``, ``viscosity``, ``density``); else None."""
    def write(self, dir: Union[str, "os.PathLike[str]"]) -> pathlib.Path:
        """Writes the outputs of ``ehl run`` into ``dir``, atomically (nothing half-written;
        ``dir`` replaced only if ehl wrote it or it is empty) and returns it as a
        ``pathlib.Path``. Raises ``ehl.OutputError``. Not interruptible: Ctrl-C during a
        write takes effect when the write has ended, so ``dir`` is complete (or, on an error,
        as it was)."""

def cancel_all() -> int:
    """Cancels every solve running now in this process, in any thread, and returns how many.
    Each stops within a solver iteration and raises KeyboardInterrupt in its own thread;
    solves started later are not affected. Ctrl-C reaches the main thread only, so with
    solves in worker threads: ``except KeyboardInterrupt: ehl.cancel_all(); raise``."""

def _solve(
    case: Case,
    callback: Optional[Callable[[float, str], None]] = None,
    poll: float = 0.05,
) -> Solution: ...

def _case_from_state(text: str, file: str, overrides: List[str]) -> Case:
    """A case from its pickled state (``Case.__reduce__``)."""

def _exception_for(kind: str, reason: str) -> BaseException:
    """The exception that a library error of ``kind`` ("case", "case-file", "output",
    "solver", "cancelled") becomes, returned, not raised (the error mapping's tests)."""
