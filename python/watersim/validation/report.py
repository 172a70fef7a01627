"""What a sweep's run records say: convergence orders, Pareto fronts, the cheapest run that
meets a case's accuracy target, and the Markdown + PNG report of ``watersim validate``.

The analysis functions are pure (lists of run records in, numbers out) and unit-tested on
synthetic records; :func:`write_report` draws with matplotlib's Agg backend.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from .._files import write_text_atomic

__all__ = [
    "ConvergenceOrder",
    "cheapest_meeting",
    "convergence_order",
    "ok_runs",
    "pareto_front",
    "self_convergence",
    "settings_label",
    "write_report",
]

Record = Mapping[str, Any]

SERIES: tuple[tuple[str, str, str], ...] = (
    ("front", "front_t", "front_x"),
    ("column height", "front_t", "height_h"),
)
"""Time series in a record's ``details`` whose self-convergence the report shows: (label,
times key, values key); the dam breaks record the front, dambreak2d also the column height."""

FLAT_ORDER = 0.2
"""An observed order below this in magnitude is reported as a level error, neither falling nor
rising with dp."""


def _error(record: Record, metric: str) -> float | None:
    """The size of a run's error ``metric`` (a signed error, as cylinder3d's, compares by its
    magnitude: targets, Pareto fronts and log axes), None when missing or not finite."""
    value = (record.get("errors") or {}).get(metric)
    if value is None:
        return None
    v = float(value)
    return abs(v) if math.isfinite(v) else None


def ok_runs(records: Sequence[Record], metric: str) -> list[Record]:
    """Runs that finished (status ``ok``) and have a finite value of ``metric``."""
    return [r for r in records if r.get("status") == "ok" and _error(r, metric) is not None]


@dataclass(frozen=True)
class ConvergenceOrder:
    """Observed order p of ``error ~ C dp^p``.

    Attributes:
        order: least-squares slope of log(error) against log(dp); positive when the error falls
            as dp falls, NaN with fewer than two distinct dp.
        n_runs: runs used (finished runs with a positive error).
        falls: whether the error of the finest run is below that of the coarsest.
        falls_every_step: whether every refinement (runs in order of decreasing dp) lowers the
            error; None with fewer than two distinct dp.
    """

    order: float
    n_runs: int
    falls: bool | None
    falls_every_step: bool | None = None


def convergence_order(dp: Sequence[float], error: Sequence[float]) -> ConvergenceOrder:
    """Least-squares slope of ``log(error)`` against ``log(dp)``.

    Errors that are zero or not finite are left out (log undefined).
    """
    pairs = [(float(d), float(e)) for d, e in zip(dp, error, strict=True)
             if d is not None and e is not None and d > 0 and math.isfinite(e) and e > 0]
    if len({d for d, _ in pairs}) < 2:
        return ConvergenceOrder(math.nan, len(pairs), None)
    x = np.log([d for d, _ in pairs])
    y = np.log([e for _, e in pairs])
    slope = float(np.polyfit(x, y, 1)[0])
    by_dp = [e for _, e in sorted(pairs, reverse=True)]  # coarsest first
    every_step = all(b < a for a, b in zip(by_dp, by_dp[1:], strict=False))
    return ConvergenceOrder(slope, len(pairs), by_dp[-1] < by_dp[0], every_step)


def settings_label(record: Record) -> str:
    """The run's numerical ``--set`` items (``details.settings``) as ``key=value, ...`` in key
    order, or ``default`` for a run without any."""
    settings = (record.get("details") or {}).get("settings") or {}
    return ", ".join(f"{k}={settings[k]}" for k in sorted(settings)) or "default"


def pareto_front(records: Sequence[Record], metric: str, cost: str = "wall_s") -> list[Record]:
    """The runs no other run beats on both ``cost`` (wall time, or ``cpu_s``) and ``metric``
    (finished runs only), sorted by cost: each is cheaper or more accurate than every other."""
    runs = sorted(ok_runs(records, metric),
                  key=lambda r: (float(r[cost]), _error(r, metric)))
    front: list[Record] = []
    best = math.inf
    for r in runs:
        e = _error(r, metric)
        assert e is not None
        if e < best:
            front.append(r)
            best = e
    return front


def cheapest_meeting(records: Sequence[Record], metric: str, target: float) -> Record | None:
    """The finished run with the smallest wall time whose ``metric`` is at most ``target``."""
    good = [r for r in ok_runs(records, metric) if (_error(r, metric) or 0.0) <= target]
    return min(good, key=lambda r: float(r["wall_s"])) if good else None


def self_convergence(runs: Sequence[Record], t_key: str = "front_t", x_key: str = "front_x"
                     ) -> list[tuple[Record, float]]:
    """RMS relative difference of each run's time series to the finest run's.

    For records whose ``details`` hold a series (``t_key``, ``x_key``, e.g. the dam-break
    front), each coarser finished run is interpolated at the finest run's sample times (within
    its own time range) and ``sqrt(mean(((x - x_finest) / x_finest)^2))`` is taken. This needs
    no reference data: it falls with dp when the solution converges, whatever the data say.

    Returns:
        (record, difference) for every finished run but the finest, coarsest first.
    """
    series = [r for r in runs if r.get("status") == "ok"
              and len((r.get("details") or {}).get(t_key) or []) >= 2
              and len(r["details"].get(x_key) or []) == len(r["details"][t_key])]
    if len(series) < 2:
        return []
    series.sort(key=lambda r: -float(r["dp"]))
    finest = series[-1]
    tf = np.asarray(finest["details"][t_key], dtype=float)
    xf = np.asarray(finest["details"][x_key], dtype=float)
    out = []
    for r in series[:-1]:
        t = np.asarray(r["details"][t_key], dtype=float)
        x = np.asarray(r["details"][x_key], dtype=float)
        sel = (tf >= t[0]) & (tf <= t[-1]) & np.isfinite(xf) & (xf != 0.0)
        if np.count_nonzero(sel) < 2:
            continue
        diff = (np.interp(tf[sel], t, x) - xf[sel]) / xf[sel]
        out.append((r, float(np.sqrt(np.mean(diff**2)))))
    return out


# ------------------------------------------------------------------------------------------------
# report


def _metrics_of(records: Sequence[Record]) -> list[str]:
    names: list[str] = []
    for r in records:
        for k in (r.get("errors") or {}):
            if k not in names:
                names.append(k)
    return names


def _fmt(v: Any, digits: int = 3) -> str:
    if v is None:
        return "-"
    if isinstance(v, float):
        if not math.isfinite(v):
            return "-"
        return f"{v:.{digits}g}"
    return str(v)


def _plot_case(name: str, runs: Sequence[Record], metrics: list[str], primary: str | None,
               path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    for i, metric in enumerate(metrics):
        good = sorted(ok_runs(runs, metric), key=lambda r: float(r["dp"]))
        good = [r for r in good if (_error(r, metric) or 0.0) > 0.0]
        if not good:
            continue
        colour = f"C{i % 10}"
        wall = [float(r["wall_s"]) for r in good]
        err = [_error(r, metric) for r in good]
        dps = [float(r["dp"]) for r in good]
        ax1.loglog(wall, err, "o-", color=colour, label=metric)
        order = convergence_order(dps, err)  # type: ignore[arg-type]
        label = metric if math.isnan(order.order) else f"{metric}: order {order.order:.2f}"
        ax2.loglog(dps, err, "o-", color=colour, label=label)
    if primary is not None:
        front = pareto_front(runs, primary)
        if front:
            ax1.step([float(r["wall_s"]) for r in front], [_error(r, primary) for r in front],
                     where="post", color="k", lw=2.5, alpha=0.35, marker="o", ms=12,
                     mfc="none", label=f"Pareto front ({primary})")
    for j, (what, t_key, x_key) in enumerate(SERIES):
        selfconv = self_convergence(runs, t_key, x_key)
        if not selfconv:
            continue
        dps = [float(r["dp"]) for r, _ in selfconv]
        diffs = [d for _, d in selfconv]
        label = f"{what} vs finest run (self-convergence)"
        if len(selfconv) >= 2:
            label += f": order {convergence_order(dps, diffs).order:.2f}"
        ax2.loglog(dps, diffs, "s--" if j == 0 else "D:", color="0.3", label=label)
    ax1.set_xlabel("wall time [s]")
    ax1.set_ylabel("error [-] (metre for *_m)")
    ax1.set_title(f"{name}: error against wall time")
    ax2.set_xlabel("dp [m]")
    ax2.set_title(f"{name}: error against dp (slope = order)")
    ax2.invert_xaxis()
    for ax in (ax1, ax2):
        ax.grid(True, which="both", alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7, framealpha=0.5)  # lines behind the legend stay visible
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


INTRODUCTION: tuple[str, ...] = (
    "",
    "Each case runs at several resolutions (particles per characteristic length, so",
    "dp = length / resolution; for the wave flumes snapped to",
    "depth / round(depth / dp) so the water is whole particle layers deep: each run's `dp`",
    "is the one it used). Errors are fractions (0.05 = 5 %) unless the name ends in",
    "`_m` (metres) or `_phase` (radians). The convergence order is the least-squares slope of",
    "log(error) against log(dp) over the finished runs: positive means the error falls as dp",
    "falls. The Pareto front holds the runs that no other run beats on both wall time and",
    "the case's primary error. Wall times are on a shared machine (see above); `cpu_s` is",
    "the process CPU time of the run.",
    "",
)
"""What the report's figures mean, under its header."""


def write_report(
    records: Sequence[Record],
    out_dir: str | Path,
    cases: Mapping[str, Any] | None = None,
    header: Sequence[str] = (),
) -> Path:
    """Write ``out_dir/README.md``, one ``<case>.png`` per case and, for a case with a
    ``figure``, ``<case>-measured.png`` (its own measurements).

    Args:
        records: run records (:func:`watersim.validation.running.make_record`).
        out_dir: folder (created).
        cases: the :class:`~watersim.validation.cases.Case` objects by name, for the
            descriptions, the resolution meaning and the accuracy targets (default
            :data:`~watersim.validation.cases.CASES`).
        header: Markdown lines put under the title (command, date, machine, load).

    Returns:
        The README path.
    """
    if cases is None:
        from .cases import CASES

        cases = CASES
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    names: list[str] = []
    for r in records:
        if r["case"] not in names:
            names.append(r["case"])
    names.sort(key=lambda n: list(cases).index(n) if n in cases else len(cases))
    lines = ["# Validation report: error against run time", "", *header, *INTRODUCTION,
             "## Summary", ""]
    summary: list[str] = []
    body: list[str] = []
    for name in names:
        runs = sorted((r for r in records if r["case"] == name),
                      key=lambda r: float(r["resolution"]))
        answer, section = _case_section(name, runs, cases.get(name), out)
        summary.append(f"- **{name}**: {answer}.")
        body += section
    lines += summary + [""] + body
    readme = out / "README.md"
    write_text_atomic(readme, "\n".join(lines) + "\n")
    return readme


def _plot_options(name: str, runs: Sequence[Record], primary: str, path: Path) -> None:
    """The primary error of each setting's runs against CPU time and against dp, one series
    per setting (:func:`settings_label`)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    labels = list(dict.fromkeys(settings_label(r) for r in runs))
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.4 + 0.16 * len(labels)))
    colours = plt.get_cmap("tab20")
    for i, label in enumerate(labels):
        good = sorted((r for r in ok_runs(runs, primary) if settings_label(r) == label
                       and (_error(r, primary) or 0.0) > 0.0), key=lambda r: float(r["dp"]))
        if not good:
            continue
        style = dict(color=colours(i % 20), marker="os^vDP*X<>hpd8"[i % 14], label=label)
        err = [_error(r, primary) for r in good]
        ax1.loglog([float(r["cpu_s"]) for r in good], err, "-", **style)  # type: ignore[arg-type]
        ax2.loglog([float(r["dp"]) for r in good], err, "-", **style)  # type: ignore[arg-type]
    front = pareto_front(runs, primary, "cpu_s")
    if front:
        ax1.step([float(r["cpu_s"]) for r in front], [_error(r, primary) for r in front],
                 where="post", color="k", lw=2.5, alpha=0.3, label="Pareto front")
    ax1.set_xlabel("CPU time [s]")
    ax1.set_ylabel(f"{primary} [-]")
    ax1.set_title(f"{name}: {primary} against CPU time, by setting")
    ax2.set_xlabel("dp [m]")
    ax2.set_title(f"{name}: {primary} against dp")
    ax2.invert_xaxis()
    for ax in (ax1, ax2):
        ax.grid(True, which="both", alpha=0.3)
    handles, names = ax1.get_legend_handles_labels()
    # below the panels: the settings' labels are long
    fig.legend(handles, names, loc="lower center", ncol=2, fontsize=7, frameon=False)
    fig.tight_layout(rect=(0.0, 0.03 + 0.025 * math.ceil(len(names) / 2), 1.0, 1.0))
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _options_section(name: str, runs: list[Record], case: Any, out: Path
                     ) -> tuple[str, list[str]]:
    """A case whose runs carry different numerical settings: one row per run with its
    setting, the primary error against CPU time by setting (``out/<name>.png``), each
    setting's convergence order, the Pareto front over CPU time and the cheapest run that
    meets the target, whatever its setting."""
    primary = getattr(case, "primary", None) or _metrics_of(runs)[0]
    metrics = _metrics_of(runs)
    if primary in metrics:
        metrics.remove(primary)
        metrics.insert(0, primary)
    runs = sorted(runs, key=lambda r: (settings_label(r) != "default", settings_label(r),
                                       float(r["resolution"])))
    png = f"{name}.png"
    _plot_options(name, runs, primary, out / png)
    body = [f"## {name}", ""]
    if case is not None:
        body += [f"{case.description}. Reference: {case.reference}. "
                 f"Resolution = {case.resolution_meaning}. One row per run and setting "
                 "(`--set` items, `details.settings` in runs.json).", ""]
    body += ["| setting | resolution | particles | steps | cpu [s] | status | "
             + " | ".join(metrics) + " |", "|" + "---|" * (6 + len(metrics))]
    for r in runs:
        status = r["status"] if r["status"] == "ok" else f"**{r['status']}**"
        body.append(f"| {settings_label(r)} | {_fmt(r['resolution'])} | {r['n_particles']} | "
                    f"{r['steps']} | {_fmt(r.get('cpu_s'))} | {status} | "
                    + " | ".join(_fmt(_error(r, k)) for k in metrics) + " |")
    for r in runs:
        if r["status"] != "ok":
            body.append(f"\n- {settings_label(r)}, resolution {_fmt(r['resolution'])}: "
                        f"{r['status']}: {r.get('message')}")
    labels = list(dict.fromkeys(settings_label(r) for r in runs))
    orders = [(label, [r for r in runs if settings_label(r) == label]) for label in labels]
    orders = [(label, rs) for label, rs in orders if len(ok_runs(rs, primary)) >= 2]
    if orders:
        body += ["", f"Observed convergence order of `{primary}` by setting:", ""]
        body += [_order_line(rs, primary).replace(f"- `{primary}`", f"- {label}", 1)
                 for label, rs in orders]
    front = pareto_front(runs, primary, "cpu_s")
    body += ["", f"Pareto front (`{primary}` against CPU time): " + (", ".join(
        f"{settings_label(r)} at resolution {_fmt(r['resolution'])} ({_fmt(r['cpu_s'])} s, "
        f"{_fmt(_error(r, primary))})" for r in front) or "empty") + "."]
    answer = "-"
    if case is not None:
        good = [r for r in ok_runs(runs, primary) if (_error(r, primary) or 0.0) <= case.target]
        best = min(good, key=lambda r: float(r["cpu_s"])) if good else None
        answer = (f"none of the runs meets it ({case.target_text}, metric `{primary}`)"
                  if best is None else
                  f"the cheapest run that meets {case.target_text} is {settings_label(best)} "
                  f"at resolution {_fmt(best['resolution'])} ({_fmt(best['cpu_s'])} s CPU)")
    note = getattr(case, "report_note", "") if case is not None else ""
    if note:
        body += ["", note]
    body += ["", f"**Answer:** {answer}.", "", f"![{name}]({png})", ""]
    return answer, body


def _case_section(name: str, runs: list[Record], case: Any, out: Path) -> tuple[str, list[str]]:
    """One case's section of the report (its figures drawn to ``out/<name>.png`` and, with
    the case's own ``figure``, ``out/<name>-measured.png``): the runs,
    their measured values and failures, the convergence orders, the self-convergence, the
    Pareto front; and the answer the summary repeats: the cheapest run meeting the target.
    Runs with different numerical settings: :func:`_options_section`."""
    if len({settings_label(r) for r in runs}) > 1:
        return _options_section(name, runs, case, out)
    primary = getattr(case, "primary", None)
    metrics = _metrics_of(runs)
    if primary is not None and primary in metrics:
        metrics.remove(primary)
        metrics.insert(0, primary)
    png = f"{name}.png"
    _plot_case(name, runs, metrics, primary, out / png)
    own = None
    if getattr(case, "figure", None) is not None:
        own = f"{name}-measured.png"
        case.figure(runs, out / own)
    body = [f"## {name}", ""]
    if case is not None:
        body += [f"{case.description}. Reference: {case.reference}. "
                 f"Resolution = {case.resolution_meaning}.", ""]
    body += _runs_table(runs, metrics)
    body += _details_table(runs, getattr(case, "report_details", ()))
    for r in runs:
        if r["status"] != "ok":
            body.append(f"\n- resolution {_fmt(r['resolution'])}: {r['status']}: "
                        f"{r.get('message')}")
    body += ["", "Observed convergence order (error ~ dp^p):", ""]
    body += [_order_line(runs, k) for k in metrics]
    body += _self_convergence_lines(runs)
    answer = "-"
    if case is not None and primary is not None:
        answer = _target_answer(runs, primary, case)
        front = pareto_front(runs, primary)
        body += ["", f"Pareto front (`{primary}` against wall time): " + (", ".join(
            f"resolution {_fmt(r['resolution'])} ({_fmt(r['wall_s'])} s, "
            f"{_fmt(_error(r, primary))})" for r in front) or "empty") + "."]
    note = getattr(case, "report_note", "") if case is not None else ""
    if note:
        body += ["", note]
    body += ["", f"**Answer:** {answer}.", "", f"![{name}]({png})", ""]
    if own is not None and (out / own).exists():
        body += [f"![{name}: measured]({own})", ""]
    return answer, body


def _runs_table(runs: Sequence[Record], metrics: list[str]) -> list[str]:
    """One row per run: its size, cost, status and errors."""
    lines = ["| resolution | dp [m] | particles | steps | sim time [s] | wall [s] | cpu [s] "
             "| status | " + " | ".join(metrics) + " |",
             "|" + "---|" * (8 + len(metrics))]
    for r in runs:
        errs = [_fmt(_error(r, k)) for k in metrics]
        status = r["status"] if r["status"] == "ok" else f"**{r['status']}**"
        lines.append(f"| {_fmt(r['resolution'])} | {_fmt(r['dp'], 4)} | {r['n_particles']} | "
                     f"{r['steps']} | {_fmt(r['sim_time'])} | {_fmt(r['wall_s'])} | "
                     f"{_fmt(r.get('cpu_s'))} | {status} | " + " | ".join(errs) + " |")
    return lines


def _details_table(runs: Sequence[Record], report_details: Sequence[str]) -> list[str]:
    """The measured values the case shows (``details`` of its records), one row per run."""
    shown = [k for k in report_details if any(k in (r.get("details") or {}) for r in runs)]
    if not shown:
        return []
    lines = ["", "Measured values (`details` in runs.json):", "",
             "| resolution | " + " | ".join(shown) + " |", "|" + "---|" * (1 + len(shown))]
    for r in runs:
        d = r.get("details") or {}
        lines.append(f"| {_fmt(r['resolution'])} | "
                     + " | ".join(_fmt(d.get(k), 4) for k in shown) + " |")
    return lines


def _order_line(runs: Sequence[Record], metric: str) -> str:
    """The observed convergence order of one error, and what it says."""
    good = ok_runs(runs, metric)
    order = convergence_order([float(r["dp"]) for r in good],
                              [_error(r, metric) for r in good])  # type: ignore[misc]
    if math.isnan(order.order):
        return f"- `{metric}`: not enough finished runs"
    if abs(order.order) < FLAT_ORDER and order.falls_every_step:
        # a slow but steady fall is not noise about a level: say both
        trend = (f"falls at every refinement, slowly (|p| < {FLAT_ORDER}, close to a "
                 "level error)")
    elif abs(order.order) < FLAT_ORDER:
        trend = f"stays about level (|p| < {FLAT_ORDER})"
    else:
        trend = ("falls" if order.falls else "does NOT fall") + \
            " from the coarsest to the finest run"
    return f"- `{metric}`: p = {order.order:.2f} over {order.n_runs} runs; the error {trend}"


def _self_convergence_lines(runs: Sequence[Record]) -> list[str]:
    """Each time series' difference to the finest run's (:data:`SERIES`), with its order."""
    lines: list[str] = []
    for what, t_key, x_key in SERIES:
        selfconv = self_convergence(runs, t_key, x_key)
        if not selfconv:
            continue
        finest = min((r for r in runs if r.get("status") == "ok"),
                     key=lambda r: float(r["dp"]))
        parts = ", ".join(f"resolution {_fmt(r['resolution'])}: {_fmt(d)}"
                          for r, d in selfconv)
        text = (f"Self-convergence (a labelled extra, no reference data): RMS relative "
                f"difference of the {what} to the finest run's (resolution "
                f"{_fmt(finest['resolution'])}): {parts}")
        if len(selfconv) >= 2:
            order = convergence_order([float(r["dp"]) for r, _ in selfconv],
                                      [d for _, d in selfconv])
            text += f"; observed order {order.order:.2f}"
        lines += ["", text + "."]
    return lines


def _target_answer(runs: Sequence[Record], primary: str, case: Any) -> str:
    """The cheapest run whose ``primary`` error meets the case's target, or that none does."""
    best = cheapest_meeting(runs, primary, case.target)
    if best is None:
        return f"none of the runs meets it ({case.target_text}, metric `{primary}`)"
    return (f"the cheapest run that meets {case.target_text} is resolution "
            f"{_fmt(best['resolution'])} (dp = {_fmt(best['dp'], 4)} m, "
            f"{_fmt(best['wall_s'])} s wall)")
