"""A run folder's files, read and checked before anything is drawn (summary.json, history.csv,
events.csv, force_bins.csv), and what the pictures compute from them: the impacts' impulses, the
force in bins of hub angle, what the impacts did to the Jacobi integral.
"""

import json
import math
from pathlib import Path

import numpy as np

from ._csv import FORCE_BIN_COLUMNS, Columns, DamagedFolder, columns_of, read_csv


def coordinate_count(config):
    """The generalised coordinates of a run's filament (the columns q1…, qd1…): its modes, and the
    stretch, last, when beam.axial = "extensible" (docs/model.md §12)."""
    beam = config["beam"]
    return beam["modes"] + (1 if beam.get("axial", "inextensible") == "extensible" else 0)


def history_columns(n):
    """The columns of a history.csv of n modes, in their order."""
    return list(columns_of("history.csv", n))


def read_run_table(path, required, words=None, text=(), may_be_empty=(), why_required=""):
    """A CSV file a run wrote as {column: numpy array}, read strictly (rotbeam._csv.read_csv): the
    damage a size check cannot see (a NUL byte, a letter in a number, an unknown word) raises
    DamagedFolder naming the file, the line, the column and the value. `required`: the columns it
    must have; `words`: {column: the words allowed}; `text`: free-text columns; `may_be_empty`:
    numeric columns whose value may be missing (NaN); every other column holds a number on every row."""
    return read_csv(path, Columns(tuple(required), words or {}, tuple(text), optional=tuple(may_be_empty)),
                    why_required=why_required)


def _summary_entry(summary, path, *keys):
    """summary[keys[0]][keys[1]]…, or DamagedFolder naming summary.json and the entry."""
    value = summary
    for k in keys:
        if not isinstance(value, dict) or k not in value:
            raise DamagedFolder(f"{path}: no entry {'.'.join(keys)}")
        value = value[k]
    return value


def check_summary(summary, path):
    """Raises DamagedFolder, naming summary.json (`path`) and the entry, when an entry the pictures
    read is missing or not of its kind: every one is checked before anything is drawn."""
    modes = _summary_entry(summary, path, "config", "beam", "modes")
    if isinstance(modes, bool) or not isinstance(modes, int) or not 1 <= modes <= 40:
        raise DamagedFolder(f"{path}: config.beam.modes = {json.dumps(modes)}: not a mode count (1..40)")
    casing = isinstance(summary.get("config", {}).get("surface"), dict) and \
        summary["config"]["surface"].get("shape") == "casing"
    place = ("config", "surface", "clearance_m" if casing else "depth_fraction")
    for keys, positive in ((("config", "hub", "speed_rpm"), True), (("config", "beam", "length_m"), True),
                           (("config", "hub", "radius_m"), False), (place, False),
                           (("config", "surface", "friction"), False)):
        v = _summary_entry(summary, path, *keys)
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or (positive and v <= 0):
            raise DamagedFolder(f"{path}: {'.'.join(keys)} = {json.dumps(v)[:40]}: not a "
                                f"{'positive ' if positive else ''}number")
    residual = _summary_entry(summary, path, "energy_audit_residual")
    if residual is not None and (isinstance(residual, bool) or not isinstance(residual, (int, float))):
        raise DamagedFolder(f"{path}: energy_audit_residual = {json.dumps(residual)[:40]}: not a number")
    scheme = _summary_entry(summary, path, "scheme")
    if not isinstance(scheme, str):
        raise DamagedFolder(f"{path}: scheme = {json.dumps(scheme)[:40]}: not a word")
    warnings = summary.get("warnings", [])
    if not isinstance(warnings, list) or not all(isinstance(w, str) for w in warnings):
        raise DamagedFolder(f"{path}: warnings: not a list of lines")


def check_run_files(folder):
    """The run's summary.json, once it is a run's summary and history.csv / events.csv are there at
    the sizes it recorded; raises DamagedFolder otherwise (a truncated or replaced file). The
    contents are read strictly by read_run."""
    folder = Path(folder)
    try:
        summary = json.loads((folder / "summary.json").read_text())
    except ValueError as e:
        raise DamagedFolder(f"{folder / 'summary.json'}: not valid JSON ({e})") from None
    files = summary.get("files") if isinstance(summary, dict) else None
    if not isinstance(summary, dict) or not isinstance(summary.get("config"), dict) or \
            not isinstance(files, dict) or not all(isinstance(v, dict) for v in files.values()):
        raise DamagedFolder(f"{folder / 'summary.json'}: not a rotbeam run summary (its config or files are missing)")
    check_summary(summary, folder / "summary.json")
    for name in ("history.csv", "events.csv"):
        path = folder / name
        if not path.exists():
            raise DamagedFolder(f"{path}: missing")
        recorded = files.get(name, {}).get("bytes")
        if recorded is not None and path.stat().st_size != recorded:
            raise DamagedFolder(f"{path}: {path.stat().st_size} bytes where summary.json records {recorded}: "
                                "truncated or replaced")
    return summary


def read_run(folder):
    """(history, events, summary) of a run folder: columns by name, and summary.json, all checked
    before anything is drawn (check_run_files, then every value of history.csv, events.csv and
    force_bins.csv read strictly). Raises DamagedFolder naming the file and what is wrong."""
    folder = Path(folder)
    summary = check_run_files(folder)
    n = coordinate_count(summary["config"])
    stretch = " and the stretch" if n > summary["config"]["beam"]["modes"] else ""
    history = read_csv(folder / "history.csv", modes=n,
                       why_required=f" (summary.json: config.beam.modes = {summary['config']['beam']['modes']}{stretch}; "
                                    "the files are not of one run)")
    events = read_csv(folder / "events.csv")
    if (folder / "force_bins.csv").exists():
        read_csv(folder / "force_bins.csv")
    return history, events, summary


def impact_rows(events):
    """The rows of events.csv that are impacts."""
    return [i for i, k in enumerate(events.get("kind", [])) if k == "impact"]


def impact_impulses(events):
    """(θ (°), tip Y (m), |P| (N·s)) of the impacts in events.csv: the momentum each gave the surface."""
    imp = impact_rows(events)
    if not imp:
        return np.array([]), np.array([]), np.array([])
    return (np.asarray(events["theta_deg"][imp], dtype=float), np.asarray(events["y_tip_m"][imp], dtype=float),
            np.abs(np.asarray(events["impulse_n_s"][imp], dtype=float)))


def impact_energy(h, events, summary):
    """What the impacts drawn did to the energy: {impacts, dh_j (Σ of the Jacobi integral's jumps at
    them, from the history rows before and after each), loss_j (Σ of events.csv's impact_loss_j: the
    impulses' work on the tip less a moving surface's part, ≤ 0), surface_j (Σ surface_work_j: a moving
    surface's work through the impacts' friction), hub_j (Σ of the hub's work during them)}, or None
    without impacts. E = T + U changes by loss + surface + hub at the impacts; h = E − ωH_z by
    loss + surface − ω(R × P)_z (the surface, fixed in the inertial frame, moves in the hub's)."""
    imp = impact_rows(events)
    if not imp:
        return None
    t = h["t_s"]
    dh = 0.0
    for i in imp:
        rows = np.flatnonzero(t == events["t_s"][i])
        if len(rows) < 2:
            dh = math.nan
            break
        dh += h["jacobi_j"][rows[-1]] - h["jacobi_j"][rows[0]]
    if "impact_loss_j" in events:
        loss = float(np.sum(events["impact_loss_j"][imp]))
        surface = float(np.sum(events["surface_work_j"][imp]))
    else:  # a folder written before events.csv had them: the normal impulses' work only
        p = events["impulse_n_s"][imp]
        loss = float(np.sum(p * (events["vx_before_m_s"][imp] + events["vx_after_m_s"][imp]) / 2))
        surface = 0.0
        if summary["config"].get("impact", {}).get("friction", "none") != "none":
            loss = math.nan
    return {"impacts": len(imp), "dh_j": dh, "loss_j": loss, "surface_j": surface,
            "hub_j": float(np.nansum(events["hub_work_j"][imp]))}


def relative_angle(theta_deg):
    """Hub angle in (−180°, 180°] from the surface's deepest point (θ itself for one pass)."""
    theta = np.asarray(theta_deg, dtype=float)
    return np.where(np.abs(theta) <= 180.0, theta, 180.0 - np.mod(180.0 - theta, 360.0))


def sustained(h):
    """The rows in sustained contact (sliding or stuck)."""
    return np.isin(h["phase"], ["contact", "stick"])


def along_angle(summary):
    """True where a position along the surface is the hub angle, not the tip's Y: a casing, closed
    around the hub, meets the tip at the same Y on both sides of its lobes (surfaces.md)."""
    return summary["config"].get("surface", {}).get("shape", "plane") == "casing"


def along_label(by_angle):
    """The axis label of a position along the surface (along_angle)."""
    return "hub angle from the deepest point (°)" if by_angle else "tip position Y (mm)"


def along_surface(theta_deg, y_tip_m, by_angle):
    """Positions along the surface: the hub angle in (−180°, 180°] from the deepest point, or Y (mm)."""
    return relative_angle(theta_deg) if by_angle else np.asarray(y_tip_m, dtype=float) * 1e3


def sustained_force(h, by_angle=False):
    """(position along the surface (along_surface), F_n (N)) on the rows in sustained contact, NaN
    elsewhere (so episodes do not join)."""
    contact = sustained(h)
    x = np.where(contact, along_surface(h["theta_deg"], h["y_tip_m"], by_angle), np.nan)
    f = np.where(contact, h["normal_force_n"], np.nan)
    if by_angle:  # an episode across ±180° is not joined across the axis: a gap where the angle wraps
        wraps = np.flatnonzero(np.abs(np.diff(x)) > 180.0) + 1
        x, f = np.insert(x, wraps, np.nan), np.insert(f, wraps, np.nan)
    return x, f


def force_bins(folder, h, events, summary, bin_deg=0.5):
    """The normal force in bins of hub angle: (columns, source). From the run's force_bins.csv where it
    has one; otherwise computed here from the files (each impact's |P| from events.csv, ∫F_n dt of
    sustained contact by the trapezoidal rule on history.csv's rows), with the same bins: width
    `bin_deg` from −180° over the relative hub angle, from the first bin that received momentum to
    the last, mean force = the bin's momentum / the time the hub takes to turn through it."""
    path = Path(folder) / "force_bins.csv"
    if path.exists():
        return read_csv(path), "force_bins.csv"
    bin_deg = float((summary.get("binned_force") or {}).get("bin_deg") or bin_deg)
    omega = summary["config"]["hub"]["speed_rpm"] * math.pi / 30.0
    count = int(math.ceil(360.0 / bin_deg - 1e-9))

    def index(angle):
        return np.minimum((np.mod(np.asarray(angle) + 180.0, 360.0) / bin_deg).astype(int), count - 1)

    normal = np.zeros(count)
    impacts = np.zeros(count, dtype=int)
    touched = np.zeros(count, dtype=bool)
    theta, _, impulse = impact_impulses(events)
    ok = np.isfinite(impulse)
    k = index(theta[ok])
    np.add.at(normal, k, impulse[ok])
    np.add.at(impacts, k, 1)
    touched[k] = True
    pressed = sustained(h)
    seg = pressed[:-1] & pressed[1:] & (np.diff(h["t_s"]) > 0)
    if seg.any():
        dt = np.diff(h["t_s"])[seg]
        f = 0.5 * (h["normal_force_n"][:-1][seg] + h["normal_force_n"][1:][seg])
        mid = 0.5 * (h["theta_deg"][:-1][seg] + h["theta_deg"][1:][seg])
        k = index(mid)
        np.add.at(normal, k, f * dt)
        touched[k] = True
    if not touched.any():
        return {c: np.array([]) for c in FORCE_BIN_COLUMNS}, "events.csv and history.csv"
    first, last = np.flatnonzero(touched)[[0, -1]]
    sl = slice(first, last + 1)
    lo = -180.0 + np.arange(first, last + 1) * bin_deg
    duration = bin_deg * math.pi / 180.0 / omega
    return ({"theta_from_deg": lo, "theta_to_deg": np.minimum(180.0, lo + bin_deg),
             "normal_impulse_n_s": normal[sl], "tangential_impulse_n_s": np.full(last + 1 - first, np.nan),
             "mean_normal_force_n": normal[sl] / duration, "mean_tangential_force_n": np.full(last + 1 - first, np.nan),
             "impacts": impacts[sl]}, "events.csv and history.csv")
