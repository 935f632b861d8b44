"""The pictures of a run folder (history.csv, events.csv, summary.json; force_bins.csv where the run
wrote one): normal_force_vs_y.png (sustained contact's F_n, the impacts' impulses, and the mean
force over bins of hub angle), tip_path.png (the path with close-ups, thesis Figure 13),
modal_coordinates.png, energy.png (the Jacobi integral, why impacts move it, the hub torque, and
the energy ledger)
and impacts.png. Each picture is a function returning its matplotlib figure.
"""

import math
from pathlib import Path

# rotbeam._figures first: where matplotlib is missing it says so in one line.
from ._figures import DEG, case_title, draw_all, save_figures, validity_note, warning_line

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ._runs import (along_angle, along_label, along_surface, coordinate_count, force_bins, impact_energy, impact_impulses, impact_rows, read_run, relative_angle,  # noqa: E402
                    sustained, sustained_force)
from ._surface import casing_radius, draw_surface, surface_of, surface_x  # noqa: E402


def plot_normal_force(h, events, summary, ax, label=None, by_angle=None, **style):
    """Sustained-contact F_n against the position along the surface (the tip's Y (mm), or the hub
    angle on a casing: along_angle; by_angle overrides); draws nothing (and no legend entry) for a pass
    without sustained contact. Returns whether it drew."""
    contact = sustained(h)
    if not contact.any():
        return False
    y, f = sustained_force(h, along_angle(summary) if by_angle is None else by_angle)
    line, = ax.plot(y, f, label=label, **style)
    # A row in contact between two that are not (a pass stopped at its first contact step) is no line:
    # a dot, so that nothing drawn is invisible.
    drawn = np.isfinite(y)
    alone = drawn & ~np.r_[False, drawn[:-1]] & ~np.r_[drawn[1:], False]
    if alone.any():
        ax.plot(y[alone], f[alone], "o", ms=3, color=line.get_color())
    return True


def _stems(ax, x, height, color, label, **style):
    ax.vlines(x, 0, height, color=color, lw=1, alpha=0.8)
    ax.plot(x, height, "o", color=color, ms=3.5, label=label, **style)


def force_figure(folder, h, events, summary, title):
    """normal_force_vs_y.png: the force the surface takes along it — sustained contact's F_n, the
    impacts' impulses (an impact has no force, it has momentum) and the mean force over bins of hub
    angle that puts both on one scale."""
    fig, (ax, axb) = plt.subplots(2, 1, figsize=(9, 7), gridspec_kw={"height_ratios": [3, 1.7]})
    s = summary
    by_angle = along_angle(summary)
    th_i, y_i, p_i = impact_impulses(events)
    x_i = along_surface(th_i, y_i, by_angle)
    has_contact = sustained(h).any()
    headroom = 1.35 if has_contact else 1.7  # room for the legend (and the note) above the data
    axp = None
    if has_contact:
        plot_normal_force(h, events, summary, ax, color="C0", lw=1.2, label="F_n in sustained contact (left axis)")
        ax.set_ylabel("normal force F_n (N)")
        ax.set_ylim(0, headroom * np.nanmax(np.where(sustained(h), h["normal_force_n"], np.nan)))
    if len(p_i):
        axp = ax.twinx() if has_contact else ax
        where = ", right axis" if has_contact else ""
        _stems(axp, x_i, p_i * 1e3, "C3",
               f"impact impulses |P| ({len(p_i)}, Σ {1e3 * np.nansum(p_i):.3g} mN·s{where})")
        axp.set_ylabel("impact impulse |P| (mN·s)", color="C3" if has_contact else "k")
        axp.set_ylim(0, headroom * np.nanmax(p_i) * 1e3)
        if has_contact:
            axp.tick_params(axis="y", colors="C3")
    if not has_contact and len(p_i):
        ax.text(0.02, 0.96, f"No sustained contact in this pass: the tip only struck\nthe surface "
                f"({len(p_i)} impacts). An impact gives momentum, not a force:\nits impulse is drawn here, the "
                "mean force over hub angle below.", transform=ax.transAxes, va="top", fontsize=8,
                bbox=dict(boxstyle="round", fc="white", ec="0.7"))
    elif not has_contact:
        ax.text(0.5, 0.5, "the tip did not reach the surface: no contact, no impacts", transform=ax.transAxes,
                ha="center", va="center", fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])
    ax.set_xlabel(along_label(by_angle))
    ax.grid(alpha=0.3)
    lines, labels = ax.get_legend_handles_labels()
    if axp is not None and axp is not ax:
        more = axp.get_legend_handles_labels()
        lines, labels = lines + more[0], labels + more[1]
    if lines:
        ax.legend(lines, labels, fontsize=8, loc="upper right" if not has_contact else "upper center",
                  ncol=1 if not has_contact else 2)
    if has_contact:
        peak = f"peak F_n {s['peak_normal_force_n']:.3g} N in sustained contact"
    else:
        peak = "no sustained contact, so no instantaneous peak force"
    numbers = s
    window = s.get("config", {}).get("output", {}).get("history_revolutions", 1)
    last = s.get("last_revolution")
    if isinstance(last, dict) and s.get("revolutions", 0) > 1 and window == 1:
        # The panel draws the last revolution's history: its numbers, not the whole run's.
        numbers = last
        if has_contact:
            peak = f"peak F_n {last['peak_normal_force_n']:.3g} N in sustained contact"
        title += f"\nthe last of {s['revolutions']} revolutions (revolution {last['revolution']})"
    ax.set_title(f"{title}\n{numbers['impacts']} impacts, {numbers['contact_episodes']} contact episodes, "
                 f"normal impulse {1e3 * numbers['normal_impulse_n_s']:.4g} mN·s; {peak}" + validity_note(s),
                 fontsize=9, color="C3" if validity_note(s) else "k")

    # The mean force over bins of hub angle: momentum per time, impacts and sustained contact alike.
    bins, source = force_bins(folder, h, events, summary)
    lo, hi = np.asarray(bins["theta_from_deg"], float), np.asarray(bins["theta_to_deg"], float)
    if len(lo):
        width = float(np.median(hi - lo))
        mean = np.asarray(bins["mean_normal_force_n"], float)
        axb.stairs(mean, np.append(lo, hi[-1]), color="C2", lw=1.2, fill=True, alpha=0.35,
                   label=f"mean normal force over {width:g}° bins (momentum / time)")
        with_imp = np.asarray(bins["impacts"], float) > 0
        if with_imp.any():
            axb.plot(0.5 * (lo + hi)[with_imp], mean[with_imp], "v", color="C3", ms=3.5,
                     label="bins holding impacts")
        if has_contact:
            th = relative_angle(h["theta_deg"])
            f = np.where(sustained(h), h["normal_force_n"], np.nan)
            f[1:][np.diff(th) < 0] = np.nan
            axb.plot(th, f, color="C0", lw=0.8, label="F_n in sustained contact")
        k = int(np.nanargmax(mean))
        peak_deg = 0.5 * (lo[k] + hi[k])
        axb.set_xlim(lo[0] - 2 * width, hi[-1] + 2 * width)
        axb.legend(fontsize=7, loc="upper right")
        axb.set_title(f"Mean normal force over {width:g}{DEG} bins of hub angle: peak {mean[k]:.3g} N at "
                      f"θ = {peak_deg:.4g}{DEG}\n(each bin's impulses and ∫F_n dt divided by the time the hub takes "
                      f"to turn {width:g}{DEG}; from {source})", fontsize=8)
    else:
        axb.text(0.5, 0.5, "no momentum reached the surface: nothing to bin", transform=axb.transAxes,
                 ha="center", va="center", fontsize=9)
        axb.set_xticks([])
        axb.set_yticks([])
    axb.set_xlabel(f"hub angle θ ({DEG})")
    axb.set_ylabel("force (N)")
    axb.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def tip_path_figure(h, events, summary, title):
    """tip_path.png: −X against Y (thesis Figure 13) with close-ups, and the gap against θ."""
    imp = impact_rows(events)
    surface = surface_of(summary)
    fig, axes = plt.subplots(2, 2, figsize=(11, 8))
    phase_colors = {"free": "C0", "contact": "C1", "stick": "C2"}
    X, Y = h["x_tip_m"] * 1e3, h["y_tip_m"] * 1e3

    def path(ax):
        for ph, color in phase_colors.items():
            sel = h["phase"] == ph
            if sel.any():  # above the surface line: contact samples lie on it
                ax.plot(Y[sel], -X[sel], ".", ms=1.5 if ph == "free" else 2.5, color=color, label=ph, zorder=3)
        draw_surface(ax, surface, Y, color="k", lw=0.5, label="surface", zorder=2)
        if imp:
            y_imp = events["y_tip_m"][imp]
            x_imp = np.interp(events["t_s"][imp], h["t_s"], h["x_tip_m"])
            ax.plot(y_imp * 1e3, -surface_x(surface, y_imp, x_imp) * 1e3, "v", color="C3", ms=4, label="impacts",
                    zorder=4)
        ax.set_xlabel("tip position Y (mm)")
        ax.set_ylabel("−X (mm)")
        ax.grid(alpha=0.3)

    def empty(ax, why):
        ax.text(0.5, 0.5, why, transform=ax.transAxes, ha="center", va="center", fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])

    path(axes[0, 0])
    axes[0, 0].set_title("whole pass", fontsize=9)
    axes[0, 0].legend(fontsize=7, markerscale=2)
    near = h["gap_m"] > -2e-3
    casing = surface["shape"] == "casing"
    if casing:  # a casing all round: its radius and the tip's, unrolled against the polar angle
        axes[0, 0].set_aspect("equal", adjustable="datalim")
        ax = axes[0, 1]
        phi = np.degrees(np.arctan2(h["y_tip_m"], h["x_tip_m"]))
        rho = np.hypot(h["x_tip_m"], h["y_tip_m"])
        grid = np.linspace(-180.0, 180.0, 1441)
        ax.plot(grid, (casing_radius(surface, np.radians(grid)) - surface["nominal_radius_m"]) * 1e3, color="k",
                lw=0.8, label="casing")
        for ph, color in phase_colors.items():
            sel = h["phase"] == ph
            if sel.any():
                ax.plot(phi[sel], (rho[sel] - surface["nominal_radius_m"]) * 1e3, ".", ms=1.5, color=color, label=ph)
        ax.set_xlabel(f"polar angle of the tip φ ({DEG})")
        ax.set_ylabel("radius − (r_h + L) (mm)")
        ax.set_title("unrolled: the tip's radius and the casing's", fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, markerscale=2)
    else:
        axes[0, 1].set_title("close-up: where the tip meets the surface", fontsize=9)
    if casing:
        pass
    elif near.any():
        path(axes[0, 1])
        axes[0, 1].set_xlim(Y[near].min() - 1, Y[near].max() + 1)
        x_near = surface_x(surface, h["y_tip_m"][near], h["x_tip_m"][near]) * 1e3
        if not np.isfinite(x_near).any():  # the tip beside a small workpiece: its own X
            x_near = h["x_tip_m"][near] * 1e3
        axes[0, 1].set_ylim(-np.nanmax(x_near) - 0.05, -np.nanmin(x_near) + 2.0)
    else:
        empty(axes[0, 1], "the tip never came within 2 mm of the surface")
    axes[1, 0].set_title("close-up: the first impact and the bounce back", fontsize=9)
    if imp:
        y0 = events["y_tip_m"][imp[0]] * 1e3
        x_tip0 = np.interp(events["t_s"][imp[:1]], h["t_s"], h["x_tip_m"])
        x0 = float(surface_x(surface, [y0 * 1e-3], x_tip0)[0]) * 1e3
        if not math.isfinite(x0):
            x0 = float(x_tip0[0]) * 1e3
        path(axes[1, 0])
        axes[1, 0].set_xlim(y0 - 0.5, y0 + 1.5)
        axes[1, 0].set_ylim(-x0 - 0.01, -x0 + 0.3)
    else:
        empty(axes[1, 0], "no impact in this pass")
    axes[1, 1].plot(h["theta_deg"], h["gap_m"] * 1e3, lw=0.8)
    axes[1, 1].axhline(0, color="k", lw=0.8)
    axes[1, 1].set_xlabel(f"hub angle θ ({DEG})")
    axes[1, 1].set_ylabel("gap C (mm)")
    low = np.nanmin(h["gap_m"]) * 1e3
    axes[1, 1].set_ylim((1.1 * low, -0.1 * low) if casing else (min(-5, low), 0.5))
    axes[1, 1].grid(alpha=0.3)
    axes[1, 1].set_title("gap against the hub angle", fontsize=9)
    fig.suptitle(f"Tip path — {title}" + warning_line(summary), fontsize=10,
                 color="C3" if summary.get("warnings") else "k")
    fig.tight_layout()
    return fig


def modal_figure(h, events, summary, title):
    """modal_coordinates.png: q and q̇ against θ."""
    n = coordinate_count(summary["config"])
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    modes = summary["config"]["beam"]["modes"]
    for i in range(1, n + 1):
        stretch = " (stretch)" if i > modes else ""  # an extensible filament's last coordinate
        a1.plot(h["theta_deg"], h[f"q{i}_m"] * 1e3, lw=0.8, label=f"q{i}{stretch}")
        a2.plot(h["theta_deg"], h[f"qd{i}_m_s"], lw=0.8, label=f"q̇{i}{stretch}")
    a1.set_ylabel("q (mm)")
    a2.set_ylabel("q̇ (m/s)")
    a2.set_xlabel(f"hub angle θ ({DEG})")
    for a in (a1, a2):
        a.grid(alpha=0.3)
        a.legend(fontsize=7, ncol=min(n, 6))
    a1.set_title(f"Modal coordinates — {title}" + validity_note(summary), fontsize=10,
                 color="C3" if validity_note(summary) else "k")
    fig.tight_layout()
    return fig


def energy_note(ledger):
    """Why the Jacobi integral jumps up at impacts with e < 1, with this run's numbers (impact_energy)."""
    def uj(joules):
        return f"{1e6 * joules:+.0f} µJ" if abs(joules) >= 1e-4 else f"{1e6 * joules:+.3g} µJ"

    why = ("h rises at impacts even with e < 1: the surface, fixed in the inertial frame, moves in the hub's frame,"
           "\nand its impulse P works on the tip: Δh = impact loss (≤ 0) + ωY_tP (> 0 where Y_t < 0, before the "
           "deepest point).")
    if math.isfinite(ledger["loss_j"]) and math.isfinite(ledger["dh_j"]):
        surface = ledger.get("surface_j", 0.0)
        frame = ledger["dh_j"] - ledger["loss_j"] - surface
        spinning = f" + spinning surface's work {uj(surface)}" if surface != 0.0 else ""
        why += (f"\nHere: loss {uj(ledger['loss_j'])}{spinning} + moving surface {uj(frame)} "
                f"= Δh {uj(ledger['dh_j'])} over the {ledger['impacts']} impacts;\nE = T + U: "
                f"{uj(ledger['loss_j'] + surface + ledger['hub_j'])} (loss{' + surface' if surface != 0.0 else ''} "
                f"+ the hub's impulsive work {uj(ledger['hub_j'])}).")
    elif math.isfinite(ledger["dh_j"]):
        why += f"\nHere the {ledger['impacts']} impacts change h by {uj(ledger['dh_j'])}."
    return why


def ledger_panel(ax, summary):
    """The energy ledger in the inertial frame: each energy term of summary.json's ledger_terms (the
    library's one table of them) and the energy change, over the run and over its last complete
    revolution where it has one, with the residual of each balance."""
    terms = summary.get("ledger_terms") or []
    groups = [("whole run", summary)]
    if isinstance(summary.get("last_revolution"), dict):
        groups.append((f"revolution {summary['last_revolution'].get('revolution', '')}", summary["last_revolution"]))
    if not terms:
        ax.text(0.5, 0.5, "summary.json lists no ledger terms (a run of an older rotbeam)", transform=ax.transAxes,
                ha="center", va="center", fontsize=8)
        ax.set_axis_off()
        return
    names = [t["label"] for t in terms] + ["energy change"]
    width = 0.8 / len(groups)
    x = np.arange(len(names))
    for g, (label, entry) in enumerate(groups):
        values = [float(entry.get(t["key"], float("nan"))) for t in terms] + [float(entry.get("energy_change_j", float("nan")))]
        residual = entry.get("ledger_residual_j")
        words = f"{label} (residual {float(residual) * 1e6:.2g} µJ)" if isinstance(residual, (int, float)) else label
        ax.bar(x + (g - (len(groups) - 1) / 2) * width, np.array(values) * 1e6, width, label=words,
               color=f"C{g}", hatch=None)
    ax.axhline(0, color="k", lw=0.6)
    ax.set_xticks(x)
    ax.set_xticklabels(names, fontsize=8)
    ax.set_ylabel("energy given to the filament (µJ)")
    ax.set_title("energy ledger in the inertial frame: the terms sum to the energy change", fontsize=9)
    ax.legend(fontsize=7, loc="best")


def energy_figure(h, events, summary, title):
    """energy.png: the Jacobi integral (with why impacts raise it), the hub torque against θ, and the
    energy ledger of the run (and of its last complete revolution)."""
    imp = impact_rows(events)
    fig = plt.figure(figsize=(9, 9))
    grid = fig.add_gridspec(3, 1, height_ratios=[1.1, 0.8, 0.9])
    a1 = fig.add_subplot(grid[0])
    a2 = fig.add_subplot(grid[1], sharex=a1)
    a3 = fig.add_subplot(grid[2])
    a1.plot(h["theta_deg"], (h["jacobi_j"] - h["jacobi_j"][0]) * 1e6, lw=1)
    for i in imp:
        a1.axvline(events["theta_deg"][i], color="C3", lw=0.4, alpha=0.5)
    a1.set_ylabel("h − h(0) (µJ)")
    a1.set_title(f"Jacobi integral h = T2 − T0 + U, the energy in the hub's rotating frame (red: impacts)\n"
                 f"energy-audit residual {summary['energy_audit_residual']:.2e} — {title}" + validity_note(summary),
                 fontsize=9, color="C3" if validity_note(summary) else "k")
    ledger = impact_energy(h, events, summary)
    if ledger is not None:
        a1.text(0.01, 0.97, energy_note(ledger), transform=a1.transAxes, va="top", fontsize=7,
                bbox=dict(boxstyle="round", fc="white", ec="0.7", alpha=0.9))
        top = np.nanmax(h["jacobi_j"] - h["jacobi_j"][0]) * 1e6
        bottom = np.nanmin(h["jacobi_j"] - h["jacobi_j"][0]) * 1e6
        span = max(top - bottom, 1e-9)
        a1.set_ylim(bottom - 0.05 * span, top + 0.45 * span)  # room for the note
    a2.plot(h["theta_deg"], h["hub_torque_n_m"] * 1e3, lw=0.8, color="C2")
    a2.set_ylabel("hub torque τ (mN·m)")
    a2.set_xlabel(f"hub angle θ ({DEG})")
    for a in (a1, a2):
        a.grid(alpha=0.3)
    plt.setp(a1.get_xticklabels(), visible=False)
    ledger_panel(a3, summary)
    a3.grid(alpha=0.3, axis="y")
    fig.tight_layout()
    return fig


def impacts_figure(h, events, summary, title):
    """impacts.png: V_X before and after, and e, at each impact."""
    imp = impact_rows(events)
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    if imp:
        th = events["theta_deg"][imp]
        a1.plot(th, events["vx_before_m_s"][imp], "o", ms=4, label="V_X before")
        a1.plot(th, events["vx_after_m_s"][imp], "s", ms=4, label="V_X after")
        a2.plot(th, events["restitution"][imp], "o", ms=4, color="C2")
        a1.legend(fontsize=8)
    else:
        a1.text(0.5, 0.5, "no impact in this pass", transform=a1.transAxes, ha="center", va="center")
    a1.axhline(0, color="k", lw=0.6)
    a1.set_ylabel("normal tip velocity (m/s)")
    a2.set_ylabel("restitution e")
    a2.set_ylim(-0.05, 1.05)
    a2.set_xlabel(f"hub angle θ ({DEG})")
    a1.set_title(f"{len(imp)} impacts ({summary.get('plastic_impacts', 0)} plastic) — {title}" + validity_note(summary),
                 fontsize=9, color="C3" if validity_note(summary) else "k")
    for a in (a1, a2):
        a.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def run_figures(folder, run=None):
    """[(name, figure)] of a run folder's pictures, all drawn before any is written (run: read_run's
    answer, when read already). Closes the ones drawn when one fails."""
    folder = Path(folder)
    h, events, summary = run if run is not None else read_run(folder)
    title = case_title(summary)
    return draw_all((("normal_force_vs_y", lambda: force_figure(folder, h, events, summary, title)),
                     ("tip_path", lambda: tip_path_figure(h, events, summary, title)),
                     ("modal_coordinates", lambda: modal_figure(h, events, summary, title)),
                     ("energy", lambda: energy_figure(h, events, summary, title)),
                     ("impacts", lambda: impacts_figure(h, events, summary, title))))


def plot_run(folder, out):
    """The pictures of a run folder into out: the files are read and checked and every picture is
    drawn before the folder out is made and anything is written (damaged files leave nothing)."""
    return save_figures(run_figures(folder), out)
