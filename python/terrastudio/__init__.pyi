# Type stub of the terrastudio package (docs/python.md). Arrays are numpy float64 unless noted.
import os
from typing import Any, Callable, Literal, Mapping, Sequence, TypedDict, Union

import numpy as np
import numpy.typing as npt

__version__: str
STATUS: tuple[str, ...]  # names of forces()' status codes: 0 "ok", 1 "no equilibrium", …

ArrayLike = npt.ArrayLike
FloatArray = npt.NDArray[np.float64]
Distribution = Union[tuple[float, float], Sequence[float], Mapping[str, Sequence[float]]]

class Soil:
    """A soil (docs/soils.md); fields by their file keys in file units: soil["phi_deg"]."""

    name: str
    source: str
    def __getitem__(self, key: str) -> float: ...
    def keys(self) -> list[str]: ...
    def to_dict(self) -> dict[str, Any]: ...

class Wheel:
    """A rigid wheel: radius r_m and width b_m [m]."""

    name: str
    source: str
    r_m: float
    b_m: float
    def to_dict(self) -> dict[str, Any]: ...

SoilSpec = Union[Soil, str, os.PathLike[str], Mapping[str, Any]]
WheelSpec = Union[Wheel, str, os.PathLike[str], Mapping[str, Any]]

def soil(spec: SoilSpec, **fields: float) -> Soil: ...
def wheel(spec: WheelSpec) -> Wheel: ...
def presets(kind: Literal["soils", "wheels", "scenarios"] = "soils") -> list[str]: ...
def soil_fields() -> list[dict[str, Any]]: ...
def identified_parameters() -> list[dict[str, Any]]: ...
def analyses() -> dict[str, str]: ...

class ForcesResult(TypedDict):
    Fx_N: FloatArray
    Fy_N: FloatArray
    Fz_N: FloatArray
    Mx_Nm: FloatArray
    My_Nm: FloatArray
    Mz_Nm: FloatArray
    Fb_N: FloatArray
    Fs_N: FloatArray
    entry_angle_deg: FloatArray
    exit_angle_deg: FloatArray
    sinkage_m: FloatArray
    ok: npt.NDArray[np.bool_]
    status: npt.NDArray[np.uint8]

def forces(
    soil: SoilSpec,
    wheel: WheelSpec,
    slip: ArrayLike,
    slip_angle_deg: ArrayLike = 0.0,
    load_N: ArrayLike | None = None,
    entry_angle_deg: ArrayLike | None = None,
    *,
    threads: int = 0,
    invalid_soil: Literal["raise", "flag"] = "raise",
    progress: Callable[[float], object] | None = None,
    **fields: Any,
) -> ForcesResult: ...
def run(
    analysis: str,
    soil: SoilSpec = "sandy-loam",
    wheel: WheelSpec = "A",
    *,
    conditions: Mapping[str, Any] | None = None,
    progress: Callable[[float], object] | None = None,
    **settings: Any,
) -> dict[str, Any]: ...
def sweep(
    soil: SoilSpec, wheel: WheelSpec, slips: ArrayLike | None = None, *,
    entry_angle_deg: float | None = None, **keywords: Any
) -> dict[str, Any]: ...
def stresses(
    soil: SoilSpec,
    wheel: WheelSpec,
    slip: float = 0.3,
    slip_angle_deg: float = 12.0,
    *,
    entry_angle_deg: float | None = None,
    load_N: float | None = None,
    step_deg: float = 0.01,
    **keywords: Any,
) -> dict[str, Any]: ...
def compaction(
    soil: SoilSpec = "sandy-loam",
    wheel: WheelSpec = "A",
    load_N: ArrayLike | None = None,
    slip: ArrayLike = 0.1,
    slip_angle_deg: ArrayLike = 0.0,
    *,
    profile: str | os.PathLike[str] | Mapping[str, Any] | None = None,
    depth_m: float = 0.3,
    **settings: Any,
) -> dict[str, Any]: ...
def traction(
    soil: SoilSpec = "sandy-loam",
    wheel: WheelSpec = "A",
    load_N: float | None = None,
    slip_angle_deg: float = 0.0,
    *,
    objective: str = "efficiency",
    max_sinkage_m: float | None = None,
    posterior: str | os.PathLike[str] | Mapping[str, Any] | None = None,
    **settings: Any,
) -> dict[str, Any]: ...
def field(
    path: str | os.PathLike[str], *, traversability: Mapping[str, Any] | None = None
) -> dict[str, Any]: ...
def identify(
    data: str | os.PathLike[str] | Mapping[str, ArrayLike] | None,
    wheel: WheelSpec,
    soil: SoilSpec = "sandy-loam",
    *,
    threads: int = 1,
    **settings: Any,
) -> dict[str, Any]: ...
def simulate(scenario: str | os.PathLike[str] = "straight", **settings: Any) -> dict[str, Any]: ...
def compare_controllers(
    scenario: str | os.PathLike[str],
    *,
    progress: Callable[[float], object] | None = None,
    **settings: Any,
) -> list[dict[str, Any]]: ...
def scenario_soils(scenario: str | os.PathLike[str]) -> dict[str, Soil]: ...
def mission_cases(
    scenario: str | os.PathLike[str],
    samples: int,
    *,
    soil_spread: Mapping[str, float] | None = None,
    chassis_mass_kg: tuple[float, float] | None = None,
    wheels: Sequence[Wheel | str] | None = None,
    seed: int = 1,
    posterior: Mapping[str | int, str | os.PathLike[str] | Mapping[str, Any]] | None = None,
) -> list[dict[str, Any]]: ...
def mission_study(
    scenario: str | os.PathLike[str],
    cases: Sequence[Mapping[str, Any]],
    *,
    client: Any = None,
    threads: int = 1,
    progress: Callable[[float], object] | None = None,
    **settings: Any,
) -> list[dict[str, Any]]: ...
def sobol(
    soil: SoilSpec,
    wheel: WheelSpec,
    parameters: Mapping[str, Distribution],
    slip: ArrayLike = (0.1, 0.3, 0.6),
    slip_angle_deg: float | Sequence[float] = 0.0,
    load_N: float | None = None,
    entry_angle_deg: float | None = None,
    outputs: str | Sequence[str] = ("Fx_N",),
    samples: int = 4096,
    seed: int = 1,
    *,
    correlated: Mapping[str, Any] | None = None,
    posterior: str | os.PathLike[str] | Mapping[str, Any] | None = None,
    resamples: int = 1000,
    confidence: float = 0.95,
    max_failed_fraction: float = 0.05,
    client: Any = None,
    chunks: int | None = None,
    threads: int = 0,
    progress: Callable[[float], object] | None = None,
    **options: Any,
) -> dict[str, Any]: ...
def morris(
    soil: SoilSpec,
    wheel: WheelSpec,
    parameters: Mapping[str, tuple[float, float]],
    slip: ArrayLike = (0.1, 0.3, 0.6),
    slip_angle_deg: float | Sequence[float] = 0.0,
    load_N: float | None = None,
    entry_angle_deg: float | None = None,
    outputs: str | Sequence[str] = ("Fx_N",),
    trajectories: int = 64,
    levels: int = 4,
    seed: int = 1,
    *,
    resamples: int = 1000,
    confidence: float = 0.95,
    max_failed_fraction: float = 0.05,
    client: Any = None,
    chunks: int | None = None,
    threads: int = 0,
    progress: Callable[[float], object] | None = None,
    **options: Any,
) -> dict[str, Any]: ...
def sobol_design(
    parameters: Mapping[str, Distribution],
    samples: int = 4096,
    seed: int = 1,
    correlated: Mapping[str, Any] | None = None,
) -> FloatArray: ...
def sobol_indices(
    parameters: Mapping[str, Distribution],
    values: ArrayLike,
    samples: int = 4096,
    seed: int = 1,
    *,
    correlated: Mapping[str, Any] | None = None,
    resamples: int = 1000,
    confidence: float = 0.95,
    threads: int = 0,
) -> dict[str, Any]: ...
