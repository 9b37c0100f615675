"""TerraStudio from Python: the wheel-soil model of the studio and the command line (docs/python.md).

Every number comes from the C++ core (the same code as ``terrastudio`` on the command line and the
studio): this package only broadcasts arrays, names keywords and shapes the results.

    >>> import numpy as np, terrastudio as ts
    >>> soil, wheel = ts.soil("sandy-loam"), ts.wheel("A")
    >>> out = ts.forces(soil, wheel, slip=np.linspace(0, 0.9, 91), slip_angle_deg=5.0, load_N=58.86)
    >>> out["Fx_N"], out["sinkage_m"], out["ok"]

Bad input raises ValueError with the command line's message (field, value, allowed range).
"""

import math
import os
import warnings

import numpy as np

from . import _core, _layout
from ._core import (STATUS, Soil, Wheel, analyses, identified_parameters, presets, sobol_design,
                    soil, soil_fields, wheel)

__version__ = _core.__version__
__all__ = [
    "STATUS",
    "Soil",
    "Wheel",
    "analyses",
    "compaction",
    "forces",
    "identified_parameters",
    "identify",
    "morris",
    "presets",
    "run",
    "simulate",
    "compare_controllers",
    "mission_cases",
    "mission_study",
    "scenario_soils",
    "sobol",
    "sobol_design",
    "sobol_indices",
    "soil",
    "soil_fields",
    "stresses",
    "sweep",
    "traction",
    "field",
    "wheel",
]

_core._set_data_dir(os.path.normpath(os.path.join(os.path.dirname(__file__), _layout.DATA_DIR)))

# Keywords of forces(), sobol() and morris() that choose the contact model (the command line's
# model flags); every other keyword of forces() is a soil field.
_MODEL_OPTIONS = ("exit_angle_deg", "rut_ratio", "max_stress_angle_deg", "bulldozing", "model",
                  "compaction")
# The keys of the operating conditions (a run script's "conditions").
_CONDITIONS = ("load_N", "slip_angles_deg", "slip_count", "slip_max", "model")
_OUTPUTS = (
    "Fx_N",
    "Fy_N",
    "Fz_N",
    "Mx_Nm",
    "My_Nm",
    "Mz_Nm",
    "Fb_N",
    "Fs_N",
    "entry_angle_deg",
    "exit_angle_deg",
    "sinkage_m",
)


def _plain(value):
    """json.dumps' fallback: numpy arrays and scalars as lists and numbers."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    raise TypeError(f"{type(value).__name__} is not a number, string, list or dict")


def _non_finite(value, path=""):
    """The key path of the first NaN or infinity in an object passed to the core, worded as the
    command line words it ("load_N: nan is not a finite number"); None when there is none."""
    if isinstance(value, dict):
        for key, item in value.items():
            found = _non_finite(item, f"{path}.{key}" if path else str(key))
            if found:
                return found
    elif isinstance(value, (list, tuple)):
        for i, item in enumerate(value):
            found = _non_finite(item, f"{path}[{i}]")
            if found:
                return found
    elif hasattr(value, "tolist"):
        return _non_finite(value.tolist(), path)
    elif isinstance(value, float) and not math.isfinite(value):
        return f"{path}: {value} is not a finite number"
    return None


def _as_soil(value):
    return value if isinstance(value, Soil) else soil(value)


def _as_wheel(value):
    return value if isinstance(value, Wheel) else wheel(value)


def _broadcast(arrays):
    """The arrays broadcast together: (shape, {name: flat float64 array of size(shape) or 1})."""
    converted = {}
    for name, value in arrays.items():
        try:
            converted[name] = np.asarray(value, dtype=np.float64)
        except (TypeError, ValueError) as e:
            raise ValueError(f"{name}: expected numbers ({e})") from None
    try:
        shape = np.broadcast_shapes(*(a.shape for a in converted.values()))
    except ValueError:
        shapes = ", ".join(f"{n} {a.shape}" for n, a in converted.items() if a.ndim > 0)
        raise ValueError(f"the arrays do not broadcast together: {shapes}") from None
    flat = {}
    for name, a in converted.items():
        if a.size == 1:
            flat[name] = a.reshape(1)  # one value for every sample, never copied N times
        else:
            flat[name] = np.ascontiguousarray(np.broadcast_to(a, shape)).reshape(-1)
    return shape, flat


def forces(soil, wheel, slip, slip_angle_deg=0.0, load_N=None, entry_angle_deg=None, *,
           threads=0, invalid_soil="raise", progress=None, **fields):
    """Forces, moments and sinkage of the wheel at every operating point.

    soil, wheel: Soil and Wheel, or what soil() and wheel() take (a preset name, a file, a dict).
    slip: s [-] in [-1, 1]; slip_angle_deg: beta [deg]; load_N: W [N] > 0 (theta_f solved so that
    F_z = W, thesis section 2.6.1) or entry_angle_deg: theta_f [deg] given.
    fields: soil fields by their file keys and units (phi_deg, c_kPa, K_m, n, kc, kphi, ...; see
    soil_fields()) replacing the soil's value per sample, and the model options exit_angle_deg,
    rut_ratio, max_stress_angle_deg, bulldozing ("bekker", "hegedus"), model ("full",
    "quadratic"). Every array argument broadcasts with the others (numpy rules).
    threads: worker threads (0: one per hardware thread; the numbers do not depend on it). The
    GIL is released while the core computes.
    invalid_soil: "raise" (ValueError naming the sample, the field, the value and its range) or
    "flag" (such samples get status 3 and NaN; for sampled distributions).
    progress: None or a callable(fraction) called about every 50 ms from the calling thread.
    Ctrl-C (KeyboardInterrupt) stops the computation within about 1 % of it, here as in every
    long call of the module (run, sweep, identify, simulate, sobol, morris).

    Returns a dict of arrays of the broadcast shape: Fx_N, Fy_N, Fz_N, Mx_Nm, My_Nm, Mz_Nm, Fb_N,
    Fs_N [N, N*m], entry_angle_deg, exit_angle_deg [deg], sinkage_m [m] (NaN where there is no
    result), ok (bool: an equilibrium was found) and status (uint8 codes, names in STATUS).
    """
    options = {k: fields.pop(k) for k in list(fields) if k in _MODEL_OPTIONS}
    arrays = {"slip": slip, "slip_angle_deg": slip_angle_deg}
    if load_N is not None:
        arrays["load_N"] = load_N
    if entry_angle_deg is not None:
        arrays["entry_angle_deg"] = entry_angle_deg
    arrays.update(fields)
    shape, flat = _broadcast(arrays)
    count = math.prod(shape)
    out = _core._forces(
        _as_soil(soil), _as_wheel(wheel), count, flat.pop("slip"), flat.pop("slip_angle_deg"),
        flat.pop("load_N", None), flat.pop("entry_angle_deg", None), flat, options, int(threads),
        invalid_soil, progress)
    result = {name: out[name].reshape(shape) for name in _OUTPUTS}
    result["status"] = out["status"].reshape(shape)
    result["ok"] = result["status"] == 0
    return result


def _split_conditions(keywords):
    conditions = {k: keywords.pop(k) for k in list(keywords) if k in _CONDITIONS}
    return conditions, keywords


def run(analysis, soil="sandy-loam", wheel="A", *, conditions=None, progress=None, **settings):
    """Any analysis of the registry (analyses()) as a run script's analysis object.

    settings: the analysis's keys as in a run script (docs/user-guide.md, "Scripted runs");
    conditions: the operating conditions (load_N, slip_angles_deg, slip_count, slip_max, model).
    progress: None or a callable(fraction), as forces(); Ctrl-C stops the analysis.
    Returns {"status", "message", "tables": {name: {column: array}}, "notes", "documents"}.
    """
    return _core._run(analysis, _as_soil(soil), _as_wheel(wheel), dict(conditions or {}),
                      settings, None, progress)


def sweep(soil, wheel, slips=None, *, entry_angle_deg=None, **keywords):
    """Forces and moments against slip for each slip angle (thesis Figs. 2.18-2.26).

    slips: the slips (default: slip_count points from 0 to slip_max); slip_angles_deg (default
    5, 10, ..., 30), load_N (default 58.86) or entry_angle_deg; model options as forces().
    Returns the sweep table's columns (slip_angle_deg, slip, entry_angle_deg, exit_angle_deg,
    sinkage_m, Fx_N, ..., Fs_N: one row per point with an equilibrium) and "notes" (the points
    without one).
    """
    conditions, settings = _split_conditions(keywords)
    if slips is not None:
        settings["slips"] = np.atleast_1d(np.asarray(slips, dtype=np.float64))
    if entry_angle_deg is not None:
        settings["entry_angle_deg"] = entry_angle_deg
    out = run("forces", soil, wheel, conditions=conditions, **settings)
    table = dict(out["tables"]["sweep"])
    table["notes"] = out["notes"]
    return table


def stresses(soil, wheel, slip=0.3, slip_angle_deg=12.0, *, entry_angle_deg=None, load_N=None,
             step_deg=0.01, **keywords):
    """Normal and shear stresses over the contact at one operating point (Eqs. 2.13-2.22), exact
    and from the quadratic approximation (Eqs. 2.36-2.38), with the approximation's errors.

    entry_angle_deg given, or solved so that F_z = load_N (default 58.86 N). Returns {"stresses":
    {theta_deg, sigma_kPa, tau_kPa, ...}, "errors": {stress_index, rmse_kPa, mae_kPa},
    "entry_angle_deg", "max_stress_angle_deg", "message", "document"}; "document" is the dict
    ``terrastudio stresses --json`` prints ("errors", "grid", "status").
    """
    conditions = {} if load_N is None else {"load_N": load_N}
    settings = {"slip": slip, "slip_angle_deg": slip_angle_deg, "step_deg": step_deg}
    if entry_angle_deg is not None:
        settings["entry_angle_deg"] = entry_angle_deg
    settings.update(keywords)
    out = run("stresses", soil, wheel, conditions=conditions, **settings)
    return {
        "stresses": out["tables"]["stresses"],
        "errors": out["tables"]["errors"],
        "entry_angle_deg": out["entry_angle_deg"],
        "max_stress_angle_deg": out["max_stress_angle_deg"],
        "message": out["message"],
        "document": out["documents"][".json"],
    }


def compaction(soil="sandy-loam", wheel="A", load_N=None, slip=0.1, slip_angle_deg=0.0, *,
               profile=None, depth_m=0.3, **settings):
    """Stress at depth, compaction risk and repeated passes (docs/compaction.md).

    profile: a preset name ("loam-moist"), a path or a dict (default: the soil's own, else none);
    other settings as a run script's "compaction" (concentration, depths_m, passes, width,
    risk_stress, reload_k0_kPa_m, reload_Au_kPa_m2, shear_memory, model options).
    With scalar load_N, slip, slip_angle_deg and concentration: the dict of ``terrastudio
    compaction --json`` ("profile", "red_to_depth_m", "passes", ...). With arrays (broadcast
    together): arrays of that shape — "sigma_z_kPa", "p_kPa" and "sigma_1_kPa" at depth_m (the
    largest over the passes), "red_to_depth_m" (nan without a profile), "rut_depth_m" and
    "sinkage_m" after the last pass, "Fx_N" and "My_Nm" of the first pass, "ok" — and "results",
    the dicts themselves.
    """
    conditions_arrays = {"load_N": load_N, "slip": slip, "slip_angle_deg": slip_angle_deg,
                         "concentration": settings.pop("concentration", None)}
    given = {k: v for k, v in conditions_arrays.items() if v is not None}
    if profile is not None:
        settings["profile"] = profile if isinstance(profile, dict) else os.fspath(profile)

    def one(values):
        conditions = {}
        local = dict(settings)
        for key, value in values.items():
            if key == "load_N":
                conditions["load_N"] = float(value)
            else:
                local[key] = float(value)
        out = run("compaction", soil, wheel, conditions=conditions, **local)
        document = out["documents"].get(".json", {})
        if out["status"] != "completed" and not document.get("passes"):
            raise RuntimeError(out["message"])
        return document

    if all(np.ndim(v) == 0 for v in given.values()):
        return one(given)
    depths = settings.get("depths_m")
    base = [round(0.1 + 0.05 * i, 12) for i in range(19)] if depths is None else list(depths)
    settings["depths_m"] = sorted(set(base) | {float(depth_m)})
    names = list(given)
    arrays = np.broadcast_arrays(*[np.asarray(given[k], dtype=np.float64) for k in names])
    shape = arrays[0].shape
    keys = ("sigma_z_kPa", "p_kPa", "sigma_1_kPa", "red_to_depth_m", "rut_depth_m", "sinkage_m",
            "Fx_N", "My_Nm")
    result = {k: np.full(shape, np.nan) for k in keys}
    result["ok"] = np.zeros(shape, dtype=bool)
    results = np.empty(shape, dtype=object)
    for index in np.ndindex(shape):
        document = one({k: a[index] for k, a in zip(names, arrays)})
        results[index] = document
        rows = [r for r in document["profile"] if abs(r["depth_m"] - depth_m) < 1e-12]
        if rows:
            for k in ("sigma_z_kPa", "p_kPa", "sigma_1_kPa"):
                result[k][index] = rows[0][k]
        if "red_to_depth_m" in document:
            result["red_to_depth_m"][index] = document["red_to_depth_m"]
        passes = document["passes"]
        if passes:
            result["rut_depth_m"][index] = passes[-1]["rut_depth_m"]
            result["sinkage_m"][index] = passes[-1]["sinkage_m"]
            result["Fx_N"][index] = passes[0]["Fx_N"]
            result["My_Nm"][index] = passes[0]["My_Nm"]
        result["ok"][index] = document["status"] == "completed"
    result["results"] = results
    return result


def traction(soil="sandy-loam", wheel="A", load_N=None, slip_angle_deg=0.0, *,
             objective="efficiency", max_sinkage_m=None, posterior=None, **settings):
    """The best slip for a soil (docs/traction.md): s* that maximises the drawbar pull or the
    tractive efficiency eta = Fx r (1 - s) / My, optionally under a sinkage cap; with a posterior
    (a dict {"parameters", "mean", "covariance"} in soil keys and units, or a soil file holding
    one) the band of the objective and a robust s* (the largest lower quantile).

    Returns the dict of ``terrastudio traction --json``: "optimal_slip", "objective", "Fx_N",
    "My_Nm", "efficiency", "sinkage_m", "curve" (and "band", "robust_slip", "expected_slip").
    Raises RuntimeError when no slip meets the cap or has an equilibrium.
    """
    local = dict(settings, slip_angle_deg=float(slip_angle_deg), objective=objective)
    if max_sinkage_m is not None:
        local["max_sinkage_m"] = float(max_sinkage_m)
    if posterior is not None:
        local["posterior"] = posterior if isinstance(posterior, dict) else os.fspath(posterior)
    conditions, local = _split_conditions(local)
    if load_N is not None:
        conditions["load_N"] = float(load_N)
    out = run("traction", soil, wheel, conditions=conditions, **local)
    if out["status"] != "completed":
        raise RuntimeError(out["message"])
    return out["documents"][".json"]


def field(path, *, traversability=None):
    """A field file's summary (docs/field.md; ``terrastudio field --json``): "name", "extent_m",
    "height_m", "max_slope_deg", "mean_slope_deg", "classes", "parameters".

    traversability: None, or a dict of its settings ({"robot": "default", "headings": 8,
    "cell_m": ..., "slip_min", "slip_max", "curve_points", "quadratic"}): adds "traversability"
    with the JSON's counts and the maps as arrays, the northern row first: "slip" and "status"
    (one rows x cols array per heading; status 0 ok, 1 stall, 2 braking), "worst_slip",
    "stall_share", "slope_deg", with the cell centres "x_m", "y_m" and "heading_deg".
    Raises ValueError naming the file's or the setting's problem.
    """
    return _core._field(os.fspath(path), traversability)


def identify(data, wheel, soil="sandy-loam", *, threads=1, **settings):
    """Soil identification from wheel data (thesis chapters 4-5): the global identification on
    the full model (or, with refine=False, the decoupled fit alone) with its uncertainty.

    data: a CSV file (columns slip, entry_angle_deg, Fx_N, Fz_N, My_Nm; docs/identification.md),
    a dict of those columns as arrays, or None for synthetic data made from `soil`
    (noise_percent, seed, loads_N, slip_count). Other settings as a run script's identification
    (refine, fix, noise, skip_bad_rows, jmax_m, priors, loss, holdout, folds, starts, load_N,
    profile). jmax_m: j_max [m] held at that value, or "fit" to identify it as an eighth
    parameter (``identify --jmax fit``; with a prior of 20 ± 20 mm when the data do not
    determine it, and a flag that says so). threads: threads of the global search (1, the
    default: none started; 0: one per core, as ``identify --threads``); the same numbers
    whatever the count.

    Returns every key of ``terrastudio identify --json`` (the parameters a0, ..., K_m, jmax_m, "std",
    "flags", "covariance", "prior", "holdout", "ambiguity", "steps", "samples", ...; a test
    compares them) and "parameters" ({name: value}, with "*_std"), "curves" ({column: array}),
    "usable", "notes", "message".
    """
    progress = settings.pop("progress", None)
    if isinstance(settings.get("jmax_m"), str):
        if settings["jmax_m"] != "fit":
            raise ValueError(f"jmax_m: {settings['jmax_m']!r} is neither a length in m nor 'fit'")
        del settings["jmax_m"]
        settings["fit_jmax"] = True
    columns = None
    if isinstance(data, dict):
        columns = data
    elif data is not None:
        settings["csv"] = os.fspath(data)
    out = _core._run("identification", _as_soil(soil), _as_wheel(wheel), {}, settings, columns,
                     progress, threads)
    # An old parameter key in fix or priors ("Ks", "n"; issue 26) was read as its new one: the
    # core's note, as a DeprecationWarning.
    for note in out["notes"]:
        if "is deprecated: use" in note:
            warnings.warn(note, DeprecationWarning, stacklevel=2)
    parameters = {k: float(v[0]) for k, v in out["tables"]["parameters"].items() if len(v)}
    result = dict(out["documents"].get("-identification.json", {}))
    result.update({
        "parameters": parameters,
        "curves": out["tables"]["curves"],
        "usable": out["usable"],
        "notes": out["notes"],
        "message": out["message"],
    })
    return result


def simulate(scenario="straight", **settings):
    """A rover scenario run (thesis chapter 3): a preset name (presets("scenarios")) or a file;
    duration_s, time_step_s, model, controller ("constant-speed", "fixed-slip", "optimal",
    "oracle"), slip (the fixed set-point), traction_limited (True, False: the slip
    controllers' traction-limited mode) and the optimal controller's robust ("none", "expected",
    "quantile"), quantile, posterior_samples, posterior_method ("sigma-points", "samples") and
    identifier ("decoupled", "full": its streaming soil estimator) override the scenario's
    (docs/traction.md). Returns {"summary": {...},
    "timeseries": {column: array}, "status", "message", "notes"} (and "streaming" when the
    scenario identifies the soil as it drives). A mission scenario (docs/field.md, "Missions")
    runs the same way: its summary has "mission_completed", "path_error_rms_m" and the rest, its
    time series "path_s_m", "path_error_m" and "curvature_1_m". A field scenario's result has
    "maps" too (docs/python.md, "A field run's maps"): map name ("rut_depth_m", "passes",
    "compaction_risk", "slip", "energy_per_m_J") -> {"values": rows x cols array, row 0 the
    northern one, NaN where no data; "x0_m", "y0_m": the south-west corner; "cell_m"; "epsg":
    the field's EPSG code or None}, the values `terrastudio simulate --out DIR` writes as
    DIR/<name>.asc, .tif and .png. chassis_mass_kg, wheel
    (Wheel, preset or dict) and soils ({"base" | class code | patch number: Soil, preset or dict})
    change the robot and its soils (docs/field.md, "Mission studies").
    """
    settings = _override_json(settings)
    settings["scenario"] = os.fspath(scenario)
    out = run("rover", **settings)
    result = {"status": out["status"], "message": out["message"], "notes": out["notes"]}
    if "maps" in out:
        result["maps"] = out["maps"]
    for name, table in out["tables"].items():
        result[name] = table
    result["summary"] = _summary(out) or result.get("summary")
    return result


def compare_controllers(scenario, *, progress=None, **settings):
    """The scenario under each controller in turn (docs/traction.md, section 6): the comparison
    table of `terrastudio simulate --compare --json`, a list of one dict per controller with
    "controller", "status", "distance_m", "energy_per_m_J", "mean_efficiency",
    "energy_per_drawbar_work", "mean_drawbar_N", "drawbar_vs_oracle", "mean_slip" (per wheel),
    "slip_tracking_rms",
    "settling_time_s" and "rut_depth_m" (None where a figure is not defined). Settings as for
    simulate, without controller; progress as forces(); Ctrl-C stops it."""
    settings["scenario"] = os.fspath(scenario)
    return _core._compare_controllers(settings, progress)


def scenario_soils(scenario):
    """The soils a mission study can vary (docs/field.md, "Mission studies"): {key: Soil} by the
    keys of simulate()'s soils= override — "base", then a field's class codes ("1", "2", ...) or
    a patch terrain's patch numbers ("1", ...)."""
    return _core._scenario_soils(os.fspath(scenario))


def _override_json(case):
    """A case's overrides as the rover's settings take them: Soil and Wheel objects as dicts."""
    out = dict(case)
    if isinstance(out.get("wheel"), Wheel):
        out["wheel"] = out["wheel"].to_dict()
    if "soils" in out:
        out["soils"] = {str(k): (v.to_dict() if isinstance(v, Soil) else v)
                        for k, v in out["soils"].items()}
    return out


def _summary(out):
    """A rover run's summary document (run()'s "documents" entry named *summary*), or None."""
    summary = [v for k, v in out["documents"].items() if "summary" in k]
    return summary[0] if summary else None


def _mission(settings):
    """One case of a mission study: its summary, status and message (runs where it is called:
    locally, or on a Dask worker)."""
    out = run("rover", **settings)
    row = dict(_summary(out) or {})
    # The wall-clock speed is measured, not computed: it differs between runs and machines.
    row.pop("real_time_factor", None)
    row["status"] = out["status"]
    row["message"] = out["message"]
    return row


def _drawn_within(rng, draw, low, high):
    """A draw redrawn until every value lies in [low, high] (20 tries, then clipped)."""
    value = draw()
    for _try in range(20):
        if np.all((low <= value) & (value <= high)):
            return value
        value = draw()
    return np.clip(value, low, high)


def mission_cases(scenario, samples, *, soil_spread=None, chassis_mass_kg=None, wheels=None,
                  seed=1, posterior=None):
    """Cases for mission_study() drawn at random (numpy's PCG64 with `seed`: the same cases on
    every machine). soil_spread: {soil field key: std in its unit} (soil_fields(): "phi_deg",
    "c_kPa", "K_m", "n", ...): each of the scenario's soils (scenario_soils()) gets an independent
    Gaussian draw around its own value per case, redrawn until the field's range holds (20 tries,
    then the range's nearest end); posterior: {soil key ("base", a class code): a soil file
    holding "posterior" (``identify --save-soil``'s) or its dict}: that soil's parameters drawn
    together from the multivariate normal, correlations kept, redrawn until every value lies in
    its range (20 tries, then clipped); the soil's other fields stay its own, except k_c = 0 when
    K_s is drawn (the identification's K_s is the soil's k_phi with k_c = 0). chassis_mass_kg:
    (low, high) drawn uniformly; wheels: a list of Wheels or presets, one drawn per case. Returns
    a list of `samples` dicts of overrides."""
    samples = int(samples)
    if samples < 1:
        raise ValueError(f"samples: {samples} is not at least 1")
    rng = np.random.Generator(np.random.PCG64(int(seed)))
    nominal = scenario_soils(scenario) if soil_spread or posterior else {}
    fields = {f["key"]: f for f in soil_fields()} if soil_spread or posterior else {}
    for key in soil_spread or {}:
        if key not in fields:
            raise ValueError(f"soil_spread: '{key}' is not a soil field ({', '.join(fields)})")
    drawn = {}  # soil key -> (parameter keys, mean, Cholesky factor, lows, highs)
    for soil_key, source in (posterior or {}).items():
        soil_key = str(soil_key)
        if soil_key not in nominal:
            raise ValueError(f"posterior.{soil_key}: the scenario has no soil '{soil_key}' "
                             f"({', '.join(nominal)})")
        group = _posterior_group(source, None, {})
        keys = group["keys"]
        for k in keys:
            if k not in fields:
                raise ValueError(f"posterior.{soil_key}: '{k}' is not a soil field")
            if k in (soil_spread or {}):
                raise ValueError(f"posterior.{soil_key}: {k} is varied twice: by posterior= "
                                 "and by soil_spread=")
        mean = np.asarray(group["mean"], dtype=float)
        cov = np.asarray(group["covariance"], dtype=float)
        if mean.shape != (len(keys),) or cov.shape != (len(keys), len(keys)):
            raise ValueError(f"posterior.{soil_key}: {len(keys)} parameters, {mean.size} means "
                             f"and a {cov.shape[0]}x{cov.shape[-1]} covariance")
        try:
            factor = np.linalg.cholesky(cov)
        except np.linalg.LinAlgError:
            raise ValueError(f"posterior.{soil_key}: the covariance is not positive definite")
        lows = np.array([fields[k]["low"] for k in keys])
        highs = np.array([fields[k]["high"] for k in keys])
        drawn[soil_key] = (keys, mean, factor, lows, highs)
    if chassis_mass_kg is not None:
        mass_low, mass_high = (float(v) for v in chassis_mass_kg)
        if not 0.0 < mass_low <= mass_high:
            raise ValueError(
                f"chassis_mass_kg: ({mass_low}, {mass_high}) is not 0 < low <= high")
    choices = [_as_wheel(w) for w in wheels] if wheels else None
    cases = []
    for _ in range(samples):
        case = {}
        if soil_spread or drawn:
            soils = {}
            for key, base in nominal.items():
                if not soil_spread and key not in drawn:
                    continue
                values = base.to_dict()
                for name, std in (soil_spread or {}).items():
                    field = fields[name]
                    low, high = field["low"], field["high"]
                    centre = float(base[name])  # in the field's unit, as the spread
                    value = centre
                    for _try in range(20):
                        value = centre + float(std) * rng.standard_normal()
                        if low <= value <= high:
                            break
                    else:
                        value = min(max(value, low), high)
                    values[name] = value
                if key in drawn:
                    keys, mean, factor, lows, highs = drawn[key]
                    x = _drawn_within(rng, lambda: mean + factor @ rng.standard_normal(len(keys)),
                                      lows, highs)
                    for name, value in zip(keys, x):
                        values[name] = float(value)
                    if "kphi" in keys:
                        values["kc"] = 0.0
                values["name"] = f"{values.get('name', key)} (drawn)"
                soils[key] = values
            case["soils"] = soils
        if chassis_mass_kg is not None:
            case["chassis_mass_kg"] = float(rng.uniform(mass_low, mass_high))
        if choices:
            case["wheel"] = choices[int(rng.integers(len(choices)))].to_dict()
        cases.append(case)
    return cases


def mission_study(scenario, cases, *, client=None, threads=1, progress=None, **settings):
    """Many runs of one rover or mission scenario (docs/field.md, "Mission studies"), one per
    case: a dict of overrides — chassis_mass_kg, wheel (Wheel, preset or dict), soils ({"base" |
    class code | patch number: Soil, preset or dict}) — on top of `settings` (simulate()'s:
    duration_s, time_step_s, model, controller, slip). mission_cases() draws such cases.
    client: None (here, `threads` cases at a time) or a dask.distributed Client (one task per
    case on its workers). Every case is a pure function of its inputs, so the results are the
    same bit for bit wherever they run. progress: None or a callable(fraction), called as cases
    finish (here only). Returns one dict per case, in order: the run's summary (simulate()'s
    "summary" without the measured real_time_factor) with "status" and "message"."""
    base = dict(settings)
    base["scenario"] = os.fspath(scenario)
    runs = []
    for i, case in enumerate(cases):
        if not isinstance(case, dict):
            raise ValueError(f"cases[{i}]: expected a dict of overrides, not {type(case).__name__}")
        runs.append({**base, **_override_json(case)})
    if client is not None:
        from ._dask import run_missions

        return run_missions(client, runs)
    from concurrent.futures import ThreadPoolExecutor, as_completed

    results = [None] * len(runs)
    with ThreadPoolExecutor(max_workers=max(1, int(threads))) as pool:
        futures = {pool.submit(_mission, one): i for i, one in enumerate(runs)}
        for done, future in enumerate(as_completed(futures), start=1):
            results[futures[future]] = future.result()
            if progress is not None:
                progress(done / len(runs))
    return results


def _read_profile(name):
    """A profile preset's or file's JSON object (the study's "profile" must be an object)."""
    import json

    path = os.fspath(name)
    if not (os.sep in path or path.endswith(".json")):
        path = os.path.join(os.path.dirname(__file__), _layout.DATA_DIR, "profiles", path + ".json")
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def _compaction_study(settings):
    """compaction={"depth_m", "passes", "concentration", "risk_stress", "profile"}: the settings of
    the compaction outputs (max_sigma_z_kPa, red_to_depth_m, rut_depth_m); a profile given by
    preset name or path is read here."""
    settings = dict(settings)
    profile = settings.get("profile")
    if profile is not None and not isinstance(profile, dict):
        settings["profile"] = _read_profile(profile)
    return settings


def _study_arguments(soil, wheel, parameters, slip, slip_angle_deg, load_N, entry_angle_deg,
                     outputs, options):
    unknown = [k for k in options if k not in _MODEL_OPTIONS]
    if unknown:
        raise TypeError(f"unexpected keyword {unknown[0]!r} (model options: "
                        f"{', '.join(_MODEL_OPTIONS)})")
    if isinstance(outputs, str):
        outputs = [outputs]
    if "compaction" in options:
        options = dict(options)
        options["compaction"] = _compaction_study(options["compaction"])
    angle_axis = np.ndim(slip_angle_deg) > 0
    if load_N is None and entry_angle_deg is None:
        load_N = 58.86  # Table 2.6's 6 kg, the conditions' default
    return dict(
        soil=_as_soil(soil), wheel=_as_wheel(wheel), parameters=dict(parameters),
        slips=[float(s) for s in np.atleast_1d(slip)],
        slip_angles_deg=[float(b) for b in np.atleast_1d(slip_angle_deg)],
        load_N=None if load_N is None else float(load_N),
        entry_angle_deg=None if entry_angle_deg is None else float(entry_angle_deg),
        outputs=list(outputs), options=options, angle_axis=bool(angle_axis))


# The identification's names of the parameters whose soil keys differ (Ks_kPa is the soil's
# kphi, n0 its n) and their old keys (issue 26), from the core's one table
# (identified_parameters()): an old key that is also a soil key ("n") is the soil's.
_IDENTIFIED_TO_SOIL = {f["key"]: f["soil_key"] for f in identified_parameters()
                       if f["soil_key"] != f["key"]}
_DEPRECATED_IDENTIFIED = {f["old_key"]: f["key"] for f in identified_parameters()
                          if f["old_key"] and f["old_key"] not in {s["key"] for s in soil_fields()}}


def _identified_soil_key(key):
    if key in _DEPRECATED_IDENTIFIED:
        warnings.warn(f"posterior: {_core._deprecation_note(key)}", DeprecationWarning,
                      stacklevel=4)
        key = _DEPRECATED_IDENTIFIED[key]
    return _IDENTIFIED_TO_SOIL.get(key, key)


def _posterior_group(posterior, correlated, parameters):
    """posterior= (a soil file with "posterior", e.g. ``identify --save-soil``'s, or a dict
    {"parameters", "mean", "covariance"} in soil keys or the identification's names, or such a
    file's dict) as a
    study's correlated group; ValueError for a key also in `parameters` or both given."""
    if posterior is None:
        return correlated
    if correlated is not None:
        raise ValueError("give posterior= or correlated=, not both")
    if isinstance(posterior, dict):
        document = posterior
    else:
        import json

        with open(os.fspath(posterior), encoding="utf-8") as f:
            document = json.load(f)
    group = document.get("posterior", document)
    missing = [k for k in ("parameters", "mean", "covariance") if k not in group]
    if missing:
        raise ValueError(f"posterior: missing {', '.join(missing)}")
    # The identification's names (identify --save-soil, identify --json's "covariance") of the
    # two parameters whose soil keys differ: K_s is the saved soil's kphi (k_c = 0), n0 its n.
    keys = [_identified_soil_key(k) for k in group["parameters"]]
    twice = [k for k in keys if k in parameters]
    if twice:
        raise ValueError(f"{twice[0]} is varied twice: by posterior= and by parameters")
    return {"keys": keys, "mean": list(group["mean"]),
            "covariance": [list(row) for row in group["covariance"]]}


def sobol(soil, wheel, parameters, slip=(0.1, 0.3, 0.6), slip_angle_deg=0.0, load_N=None,
          entry_angle_deg=None, outputs=("Fx_N",), samples=4096, seed=1, *, correlated=None,
          posterior=None, resamples=1000, confidence=0.95, max_failed_fraction=0.05, client=None,
          chunks=None, threads=0, progress=None, **options):
    """Sobol' first-order and total indices of the wheel model (docs/sensitivity.md).

    parameters: {soil file key: distribution} in the file's units, in the order of the indices'
    rows; a distribution is (low, high) (uniform), {"range": [low, high]} or {"normal": [mean,
    sd], "bounds": [low, high]} (bounds optional). correlated: {"keys", "mean", "covariance"}, a
    multivariate normal group after them (an identification's posterior); posterior: the same
    from a soil file holding "posterior" (``identify --save-soil``) or its dict, in soil keys
    and units (pass that file as `soil` too, so that the fields it does not vary are its own).
    slip, slip_angle_deg: the operating points; load_N (theta_f solved per sample; 58.86 N when
    neither is given) or entry_angle_deg. outputs: any of Fx_N, Fy_N, Fz_N, Mx_Nm, My_Nm, Mz_Nm, Fb_N, Fs_N,
    sinkage_m, entry_angle_deg, exit_angle_deg, and the compaction outputs max_sigma_z_kPa,
    red_to_depth_m, rut_depth_m with compaction={"depth_m", "passes", "concentration", "profile"}
    (a preset name, a path or a dict; docs/compaction.md). samples: N base samples (N (d + 2) rows, each
    evaluated at every point); seed: the Sobol' sequence's shift and the bootstrap's seed.
    client: a dask.distributed.Client to evaluate the rows on its workers, in `chunks` pieces
    (default: 4 per worker thread); the result is bit for bit the local one.
    progress: None or a callable(fraction) (local runs; with a client, Dask's own dashboard
    shows progress); Ctrl-C stops a local study.

    Returns {"S1", "ST", "S1_conf", "ST_conf"}: {output: array [parameter, slip]} ([parameter,
    slip angle, slip] when slip_angle_deg is a list), "parameters", "outputs", "slip",
    "slip_angle_deg", "evaluations", "dropped" (base samples left out per point), "status",
    "message". Raises RuntimeError when too many evaluations failed at some point.
    """
    arguments = _study_arguments(soil, wheel, parameters, slip, slip_angle_deg, load_N,
                                 entry_angle_deg, outputs, options)
    correlated = _posterior_group(posterior, correlated, parameters)
    arguments.update(correlated=correlated, samples=int(samples), seed=int(seed),
                     resamples=int(resamples), confidence=float(confidence),
                     max_failed_fraction=float(max_failed_fraction))
    return _study("sobol", arguments, client, chunks, threads, progress)


def morris(soil, wheel, parameters, slip=(0.1, 0.3, 0.6), slip_angle_deg=0.0, load_N=None,
           entry_angle_deg=None, outputs=("Fx_N",), trajectories=64, levels=4, seed=1, *,
           resamples=1000, confidence=0.95, max_failed_fraction=0.05, client=None, chunks=None,
           threads=0, progress=None, **options):
    """Morris elementary-effects screening of the wheel model (docs/sensitivity.md).

    parameters: {soil file key: (low, high)} (uniform ranges only). The other arguments as
    sobol(). Returns {"mu_star", "mu", "sigma", "mu_star_conf"}: {output: array [parameter,
    slip]} and the keys sobol() returns besides the indices.
    """
    arguments = _study_arguments(soil, wheel, parameters, slip, slip_angle_deg, load_N,
                                 entry_angle_deg, outputs, options)
    arguments.update(trajectories=int(trajectories), levels=int(levels), seed=int(seed),
                     resamples=int(resamples), confidence=float(confidence),
                     max_failed_fraction=float(max_failed_fraction))
    return _study("morris", arguments, client, chunks, threads, progress)


def sobol_indices(parameters, values, samples=4096, seed=1, *, correlated=None, resamples=1000,
                  confidence=0.95, threads=0):
    """Sobol' indices of any model from its outputs on sobol_design(parameters, samples, seed,
    correlated): values is [rows] or [rows, outputs]. Returns {"S1", "ST", "S1_conf", "ST_conf"}
    as arrays [parameter, output] and "parameters"."""
    return _core.sobol_indices(dict(parameters), correlated, int(samples), int(seed), values,
                               int(resamples), float(confidence), int(threads))


def _plan(kind, arguments):
    return (_core._SobolPlan if kind == "sobol" else _core._MorrisPlan)(**arguments)


def _study(kind, arguments, client, chunks, threads, progress=None):
    plan = _plan(kind, arguments)
    if client is None:
        return plan.run(int(threads), progress)
    from ._dask import run_on

    return run_on(client, kind, arguments, plan, chunks, int(threads))
