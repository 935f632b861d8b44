#!/usr/bin/python3
"""Rigid against compliant (Hertz) contact: convergence in the number of modes, the rigid limit,
and what the compliant law costs (docs/contact.md).

Runs `rotbeam run` (adaptive scheme, default tolerances) and collects from each summary.json the
peak normal force, the contact time, the counts (impacts, contact episodes), the total normal
impulse, the last separation angle, the steps and the CPU time of the process:

  modes      n = 3 … 20 with contact.model = "rigid" and "hertz", on the base case (550 rpm,
             p = 2 %, μ = 0.4, Yigit's restitution) and at 3000 rpm
  stiffness  contact.stiffness_factor = 10^k (E* × 10^k), k = 0 … 6, 5 modes, against the rigid
             pass: on the base case, and with μ = 0 and a constant e = 0.5 (where the two laws
             describe the same impacts)

  cost       (--cost) the median CPU time and the steps of `rotbeam run` with either law, 5 and 10
             modes, both speeds, over --repeats runs

Results go to a JSON file (--out); --plot draws docs/images/contact_convergence.png from it and
prints the tables in Markdown. Both steps: bench/contact_convergence.py --out results.json --plot.

Usage: bench/contact_convergence.py [--rotbeam build/rotbeam] [--out FILE] [--modes 3:20]
                                    [--skip-runs] [--plot] [--image PNG] [--cost [--repeats 5]]
"""
import argparse
import json
import pathlib
import resource
import subprocess
import sys
import tempfile

REPO = pathlib.Path(__file__).resolve().parent.parent

KEYS = ["impacts", "contact_episodes", "contact_time_s", "peak_normal_force_n", "normal_impulse_n_s",
        "last_separation_deg", "steps", "rhs_evaluations", "contact_dissipation_j"]


def run_cli(rotbeam, sets):
    """One pass; returns the summary's KEYS and the CPU time of the process [s]."""
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(tmp) / "run"
        cmd = [str(rotbeam), "run", "--quiet", "-o", str(out)]
        for s in sets:
            cmd += ["--set", s]
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        proc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        if proc.returncode != 0:
            raise SystemExit(f"contact_convergence: {' '.join(cmd)} exited {proc.returncode}: {proc.stderr.strip()}")
        with open(out / "summary.json") as f:
            s = json.load(f)
    row = {k: s.get(k) for k in KEYS}
    row["cpu_s"] = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return row


CASES = {
    "550 rpm": ["hub.speed_rpm=550"],
    "3000 rpm": ["hub.speed_rpm=3000"],
}
LIMIT_CASES = {
    "base case (mu = 0.4, Yigit)": [],
    "mu = 0, e = 0.5": ["surface.friction=0", "impact.restitution=0.5"],
}


def run_all(rotbeam, modes):
    results = {"modes": {}, "stiffness": {}}
    for name, sets in CASES.items():
        for law in ("rigid", "hertz"):
            rows = []
            for n in modes:
                row = run_cli(rotbeam, sets + [f"beam.modes={n}", f"contact.model={law}"])
                row["n"] = n
                rows.append(row)
                print(f"{name} {law} n={n}: {row}", file=sys.stderr, flush=True)
            results["modes"][f"{name} {law}"] = rows
    for name, sets in LIMIT_CASES.items():
        rows = [dict(run_cli(rotbeam, sets), k=None)]
        for k in range(0, 7):
            row = run_cli(rotbeam, sets + ["contact.model=hertz", f"contact.stiffness_factor=1e{k}"])
            row["k"] = k
            rows.append(row)
            print(f"{name} k={k}: {row}", file=sys.stderr, flush=True)
        results["stiffness"][name] = rows
    return results


def cost(rotbeam, repeats):
    import statistics
    out = ["| case | n | rigid: steps | rigid: CPU [s] | hertz: steps | hertz: CPU [s] | hertz / rigid CPU |",
           "|---|---|---|---|---|---|---|"]
    for name, sets in CASES.items():
        for n in (5, 10):
            med = {}
            for law in ("rigid", "hertz"):
                rows = [run_cli(rotbeam, sets + [f"beam.modes={n}", f"contact.model={law}"]) for _ in range(repeats)]
                med[law] = (rows[0]["steps"], statistics.median(r["cpu_s"] for r in rows))
            out.append(f"| {name} | {n} | {med['rigid'][0]} | {med['rigid'][1]:.3f} | {med['hertz'][0]} | "
                       f"{med['hertz'][1]:.3f} | {med['hertz'][1] / med['rigid'][1]:.2f} |")
    return "\n".join(out)


def fmt(v, spec):
    return "—" if v is None else format(v, spec)


def tables(results):
    out = []
    for name in CASES:
        out.append(f"\n**{name}** (p = 2 %, μ = 0.4, Yigit's restitution, rigid start; adaptive scheme)\n")
        out.append("| n | rigid: impacts | episodes | contact time [ms] | peak F_n [N] | impulse [mN s] | last sep. [°] "
                   "| hertz: episodes | contact time [ms] | peak F_n [N] | impulse [mN s] | last sep. [°] |")
        out.append("|---|---|---|---|---|---|---|---|---|---|---|---|")
        rigid, hertz = results["modes"][f"{name} rigid"], results["modes"][f"{name} hertz"]
        for r, h in zip(rigid, hertz):
            out.append(f"| {r['n']} | {r['impacts']} | {r['contact_episodes']} | {r['contact_time_s'] * 1e3:.4f} | "
                       f"{r['peak_normal_force_n']:.3f} | {r['normal_impulse_n_s'] * 1e3:.4f} | "
                       f"{fmt(r['last_separation_deg'], '.3f')} | {h['contact_episodes']} | "
                       f"{h['contact_time_s'] * 1e3:.4f} | {h['peak_normal_force_n']:.3f} | "
                       f"{h['normal_impulse_n_s'] * 1e3:.4f} | {fmt(h['last_separation_deg'], '.3f')} |")
    for name, rows in results["stiffness"].items():
        rigid = rows[0]
        out.append(f"\n**Rigid limit, {name}** (550 rpm, p = 2 %, 5 modes; rigid: impulse "
                   f"{rigid['normal_impulse_n_s'] * 1e3:.5f} mN s, last separation {rigid['last_separation_deg']:.4f}°)\n")
        out.append("| E* × | episodes | peak F_n [N] | contact time [ms] | impulse [mN s] | impulse − rigid [%] | "
                   "last sep. − rigid [°] | steps |")
        out.append("|---|---|---|---|---|---|---|---|")
        for h in rows[1:]:
            dj = (h["normal_impulse_n_s"] / rigid["normal_impulse_n_s"] - 1) * 100
            ds = h["last_separation_deg"] - rigid["last_separation_deg"]
            out.append(f"| 10^{h['k']} | {h['contact_episodes']} | {h['peak_normal_force_n']:.1f} | "
                       f"{h['contact_time_s'] * 1e3:.4f} | {h['normal_impulse_n_s'] * 1e3:.5f} | {dj:+.3f} | {ds:+.4f} | "
                       f"{h['steps']} |")
    return "\n".join(out)


def plot(results, image):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 2, figsize=(11, 8))
    styles = {"rigid": dict(marker="o", color="0.35"), "hertz": dict(marker="s", color="tab:red")}
    lines = {"550 rpm": "-", "3000 rpm": "--"}
    for name in CASES:
        for law in ("rigid", "hertz"):
            rows = results["modes"][f"{name} {law}"]
            n = [r["n"] for r in rows]
            kw = dict(styles[law], linestyle=lines[name], label=f"{law}, {name}", markersize=4)
            # A pass of impacts alone has no force (0): not drawn on the log axis.
            axes[0, 0].plot(n, [r["peak_normal_force_n"] or float("nan") for r in rows], **kw)
            axes[0, 1].plot(n, [r["normal_impulse_n_s"] * 1e3 for r in rows], **kw)
            axes[1, 0].plot(n, [r["impacts"] + r["contact_episodes"] if law == "rigid" else r["contact_episodes"]
                                for r in rows], **kw)
    axes[0, 0].set_yscale("log")
    axes[0, 0].set_ylabel("peak normal force [N] (rigid: sustained contact only)")
    axes[0, 1].set_ylabel("total normal impulse [mN s]")
    axes[1, 0].set_ylabel("contacts per pass (rigid: impacts + episodes) [-]")
    axes[1, 0].set_yscale("log")
    for ax in (axes[0, 0], axes[0, 1], axes[1, 0]):
        ax.set_xlabel("number of modes n [-]")
        ax.grid(True, alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    ax = axes[1, 1]
    for name, rows in results["stiffness"].items():
        rigid = rows[0]
        k = [r["k"] for r in rows[1:]]
        ax.plot(k, [abs(r["normal_impulse_n_s"] / rigid["normal_impulse_n_s"] - 1) for r in rows[1:]], marker="o",
                label=f"|impulse/rigid − 1|, {name.replace('mu', 'μ')}")
        ax.plot(k, [abs(r["last_separation_deg"] - rigid["last_separation_deg"]) / 10.0 for r in rows[1:]],
                marker="s", linestyle="--", label=f"|last separation − rigid| / 10°, {name.replace('mu', 'μ')}")
    ax.set_yscale("log")
    ax.set_xlabel("contact stiffness E* × 10^k: k [-]")
    ax.set_ylabel("distance from the rigid pass [-]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    fig.suptitle("Rigid and Hertz contact against the number of modes (p = 2 %, μ = 0.4) and the rigid limit (5 modes, 550 rpm)")
    fig.tight_layout()
    fig.savefig(image, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rotbeam", default=str(REPO / "build" / "rotbeam"))
    ap.add_argument("--out", default="contact_convergence.json")
    ap.add_argument("--modes", default="3:20", help="first:last mode count")
    ap.add_argument("--skip-runs", action="store_true", help="only tabulate and plot --out")
    ap.add_argument("--plot", action="store_true")
    ap.add_argument("--image", default=str(REPO / "docs" / "images" / "contact_convergence.png"))
    ap.add_argument("--cost", action="store_true", help="only the cost table (median CPU over --repeats runs)")
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args()
    if args.cost:
        print(cost(args.rotbeam, args.repeats))
        return
    if not args.skip_runs:
        a, b = (int(x) for x in args.modes.split(":"))
        results = run_all(args.rotbeam, list(range(a, b + 1)))
        with open(args.out, "w") as f:
            json.dump(results, f, indent=1)
    with open(args.out) as f:
        results = json.load(f)
    print(tables(results))
    if args.plot:
        plot(results, args.image)


if __name__ == "__main__":
    main()
