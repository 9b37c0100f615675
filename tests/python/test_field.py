"""ts.field: the command line's summary and traversability, the maps as arrays."""

import json
import math
import os

import numpy as np
import pytest

import terrastudio as ts


def test_the_summary_is_the_command_lines(cli, resources):
    path = os.path.join(resources, "fields", "sloped-wet", "field.json")
    out = ts.field(path)
    run = cli("field", path, "--json")
    assert run.returncode == 0, run.stderr
    assert out == json.loads(run.stdout)


def test_traversability_maps(cli, resources, tmp_path):
    path = os.path.join(resources, "fields", "sloped-wet", "field.json")
    out = ts.field(path, traversability={"robot": "wheel-b", "headings": 4, "cell_m": 2.0})
    t = out["traversability"]
    assert len(t["slip"]) == 4 and t["slip"][0].shape == (20, 30)
    assert t["x_m"][0] == 1.0 and t["y_m"][0] == 39.0  # the northern row first
#The counts of the JSON are the maps' statuses.
    for h, heading in enumerate(t["headings"]):
        assert heading["stalled"] == int(np.sum(t["status"][h] == 1))
        assert heading["braking"] == int(np.sum(t["status"][h] == 2))
#On the plane(8 % along x, 3 % across; away from the hollow) uphill(heading 0) needs more
#slip than across(heading 90).
    plane_deg = math.degrees(math.atan(math.hypot(0.08, 0.03)))
    on_plane = np.abs(t["slope_deg"] - plane_deg) < 0.01
    both = on_plane & np.isfinite(t["slip"][0]) & np.isfinite(t["slip"][1])
    assert np.sum(both) > 300
    assert np.all(t["slip"][0][both] >= t["slip"][1][both])
    run = cli("field", path, "--robot", "wheel-b", "--headings", 4, "--cell", 2,
              "--traversability", tmp_path / "t.csv", "--json")
    assert run.returncode == 0, run.stderr
    expected = json.loads(run.stdout)["traversability"]
    assert {
k: t[k] for k in expected
} == expected


def test_bad_settings_name_the_field(resources):
    path = os.path.join(resources, "fields", "sloped-wet", "field.json")
    with pytest.raises(ValueError, match="headings"):
        ts.field(path, traversability={"headings": 0})
    with pytest.raises(ValueError, match="nowhere"):
        ts.field("nowhere.json")
    assert math.isfinite(ts.field(path)["max_slope_deg"])


def _read_asc(path):
    """An ESRI ASCII grid as (header, values with NaN for no data), parsed here."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    header = {}
    for line in lines[:6]:
        key, value = line.split()
        header[key.lower()] = float(value)
    values = np.array([[float(v) for v in line.split()] for line in lines[6:] if line.strip()])
    values[values == header["nodata_value"]] = np.nan
    return header, values


def _tiff_tags(path):
    """The first image's tags of a little-endian TIFF, parsed here (no libtiff): tag -> values."""
    import struct
    with open(path, "rb") as f:
        data = f.read()
    assert data[:4] == b"II*\0"
    (ifd,) = struct.unpack_from("<I", data, 4)
    (count,) = struct.unpack_from("<H", data, ifd)
    sizes = {1: ("B", 1), 2: ("s", 1), 3: ("H", 2), 4: ("I", 4), 12: ("d", 8)}
    tags = {}
    for k in range(count):
        tag, kind, n, value = struct.unpack_from("<HHII", data, ifd + 2 + 12 * k)
        code, size = sizes[kind]
        at = ifd + 2 + 12 * k + 8 if n * size <= 4 else value
        if code == "s":
            tags[tag] = data[at:at + n].rstrip(b"\0").decode()
        else:
            tags[tag] = struct.unpack_from(f"<{n}{code}", data, at)
    return tags


def test_a_field_runs_maps_are_the_files_the_command_line_writes(cli, tmp_path):
    out = ts.simulate("field-slope-wet", duration_s=3)
    maps = out["maps"]
    assert list(maps) == ["rut_depth_m", "passes", "compaction_risk", "slip", "energy_per_m_J"]
    run = cli("simulate", "--scenario", "field-slope-wet", "--duration", 3, "--out", tmp_path)
    assert run.returncode == 0, run.stderr
    for name, m in maps.items():
        for ext in ("asc", "tif", "png"):
            assert f"{tmp_path}/{name}.{ext}" in run.stdout
        header, values = _read_asc(tmp_path / f"{name}.asc")
        assert m["values"].shape == (header["nrows"], header["ncols"]) == (400, 600)
        assert (m["x0_m"], m["y0_m"], m["cell_m"]) == (
            header["xllcorner"], header["yllcorner"], header["cellsize"])
        assert m["epsg"] is None  # the shipped field's rasters are ESRI ASCII grids
        np.testing.assert_array_equal(m["values"], values)  # NaN where no data, in both
#The GeoTIFF's georeferencing, read from its bytes: 600 x 400 Float64 cells of 0.1 m,
#the tie point at the lower - left corner, PixelIsArea, metres, no data NaN.
        tags = _tiff_tags(tmp_path / f"{name}.tif")
        assert (tags[256], tags[257], tags[258], tags[339]) == ((600,), (400,), (64,), (3,))
        assert tags[33550] == (m["cell_m"], m["cell_m"], 0.0)
        assert tags[33922] == (0.0, 400.0, 0.0, m["x0_m"], m["y0_m"], 0.0)
        keys = tags[34735]
        geo = {keys[4 + 4 * k]: keys[7 + 4 * k] for k in range(keys[3])}
        assert geo == {1024: 1, 1025: 1, 3072: 32767, 3076: 9001}
        assert tags[42113] == "nan"
    assert np.nanmax(maps["rut_depth_m"]["values"]) > 0.0
    assert np.nanmax(maps["passes"]["values"]) >= 1.0
#A patch scenario has no maps.
    assert "maps" not in ts.simulate("straight", duration_s=0.2)
