"""The surface in the pictures, from one place: what a run wrote of it (summary.json `surface`, by
Surface::describe in src/surface/: a plane at `distance_m`; a cylinder of `radius_m` whose centre
is at `centre_x_m`; a casing of `nominal_radius_m` (r_h + L), `clearance_m` and `lobes` of
`lobe_amplitude_m` by its `lobe_law`, docs/surfaces.md), drawn in the thesis's plane: Y to the
right, −X up. Every picture, animation and figure takes its outline, its X at a tip's Y and the
words of its title from here.
"""

import numpy as np


def surface_of(summary):
    """The surface as the run described it (summary.json `surface`). Folders written before the
    surface described itself hold the thesis's plane, rebuilt here from their configuration."""
    if "surface" in summary:
        return summary["surface"]
    c = summary["config"]
    return {"shape": "plane",
            "distance_m": c["hub"]["radius_m"] + c["beam"]["length_m"] * (1 - c["surface"]["depth_fraction"])}


def casing_radius(surface, phi):
    """ρ = r_h + L + c(φ) (m) of a casing (summary.json `surface`) at the polar angles φ (rad), by the
    clearance law of docs/surfaces.md."""
    phi = np.asarray(phi, dtype=float)
    c0, lobes, a = surface["clearance_m"], surface.get("lobes", 0), surface.get("lobe_amplitude_m", 0.0)
    c = np.full_like(phi, c0)
    if lobes and surface.get("lobe_law", "cosine") == "benchmark":
        m = np.mod(phi + np.pi / 2, np.pi)
        c = c0 - 2 * a * np.exp(-((m / np.pi - 0.5) / 0.15) ** 2)
    elif lobes:
        c = c0 - a * np.cos(lobes * phi)
    return surface["nominal_radius_m"] + c


def surface_x(surface, y, x_hint=None):
    """X (m) of the surface at the global Y values `y` (m), for drawing it in the (Y, −X) plane: a
    cylinder's near side; for a casing, the side of x_hint's sign (X > 0 without it)."""
    y = np.asarray(y, dtype=float)
    shape = surface["shape"]
    if shape == "plane":
        return np.full_like(y, surface["distance_m"])
    if shape == "cylinder":
        r = surface["radius_m"]
        with np.errstate(invalid="ignore"):
            return surface["centre_x_m"] - np.sqrt(r * r - y * y)
    if shape == "casing":
        if x_hint is not None:  # the casing on the ray through (x_hint, y): exact where the tip touches it
            phi = np.arctan2(y, np.asarray(x_hint, dtype=float))
            return casing_radius(surface, phi) * np.cos(phi)
        x = np.full_like(y, surface["nominal_radius_m"])
        with np.errstate(invalid="ignore"):
            for _ in range(8):  # ρ(φ) with φ = atan2(Y, X): a fixed point, the lobes being shallow
                rho = casing_radius(surface, np.arctan2(y, x))
                x = np.sqrt(rho * rho - y * y)
        return x
    raise ValueError(f"cannot draw a surface of shape {shape!r}")


def outline(surface, y_mm):
    """The surface's curve (Y, −X) in mm over the Y values `y_mm` (their span; a casing: whole,
    closed, and y_mm may be None)."""
    if surface["shape"] == "casing":  # 64 points a lobe at least: no aliasing of many lobes
        phi = np.linspace(-np.pi, np.pi, max(2881, 64 * int(surface.get("lobes", 0)) + 1))
        rho = casing_radius(surface, phi)
        return rho * np.sin(phi) * 1e3, -rho * np.cos(phi) * 1e3
    if surface["shape"] == "cylinder":  # by angle, the near half, finely enough for the close-ups
        r, cx = surface["radius_m"], surface["centre_x_m"]
        lo, hi = np.nanmin(y_mm) * 1e-3, np.nanmax(y_mm) * 1e-3
        a = np.linspace(np.arcsin(np.clip(lo / r, -1, 1)), np.arcsin(np.clip(hi / r, -1, 1)), 4001)
        return r * np.sin(a) * 1e3, -(cx - r * np.cos(a)) * 1e3
    y = np.linspace(np.nanmin(y_mm), np.nanmax(y_mm), 200)
    return y, -surface_x(surface, y * 1e-3) * 1e3


def draw_surface(ax, surface, y_mm, **style):
    """The surface as a curve −X against Y (mm) over the Y values `y_mm` (a casing: whole, closed)."""
    return ax.plot(*outline(surface, y_mm), **style)


def casing_words(surface, law=True):
    """'clearance 0.1 mm, 2 cosine lobes of 0.3 mm' of a casing for a title (law: with the lobe law)."""
    lobes = int(surface.get("lobes", 0))
    kind = f"{surface.get('lobe_law', 'cosine')} " if law else ""
    shape = (f", {lobes} {kind}lobe{'s' if lobes != 1 else ''} of {1e3 * surface.get('lobe_amplitude_m', 0):g} mm"
             if lobes else ", concentric")
    return f"clearance {1e3 * surface.get('clearance_m', 0):g} mm{shape}"


def surface_words(config):
    """The surface of a configuration in a few words for a title: the depth (plane), the workpiece
    (cylinder) or the casing's clearance and lobes."""
    s = config["surface"]
    shape = s.get("shape", "plane")
    if shape == "casing":
        return "casing " + casing_words(s, law=False)
    depth = f"depth {100 * s['depth_fraction']:g} %"
    if shape == "cylinder":
        spin = s.get("speed_rpm", 0)
        radius = f"{1e3 * s['radius_m']:g} mm" if s["radius_m"] < 10 else f"{s['radius_m']:g} m"
        return f"cylinder R {radius}{f' at {spin:g} rpm' if spin else ''}, {depth}"
    return depth


def reach_m(config):
    """How far (m) the undeformed tip reaches into the surface of a configuration, the scale of a
    close-up: the depth p·L (plane, cylinder), or a casing's clearance or lobes (at least 0.1 mm)."""
    s = config["surface"]
    if s.get("shape") == "casing":
        return max(abs(s["clearance_m"]), 2 * s.get("lobe_amplitude_m", 0.0), 1e-4)
    return s["depth_fraction"] * config["beam"]["length_m"]
