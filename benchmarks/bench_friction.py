"""What Coulomb friction and a finite layer cost contactlib's solver, and its confined layer against
ContactMechanics'.

Three measurements in one run, each printed as a markdown table (machine, versions and git
revision in the header) and written with every number to ``--json``:

1. **friction**: a frictional solve (``friction = --frictions``, 0.5 and 1.0) over the frictionless
   solve of the same scene (same surface, load and ``--tol``). Scenes (``--scenes``):
   ``half-space`` (``--nu`` 0.3: the material coupling ``(1 - 2 nu) / (2 (1 - nu))``),
   ``confined`` (a confined layer, ``--layer-nu`` 0.5, ``q0 h = 1`` with ``q0 = 2 pi / L``: the
   geometric coupling) and, on request, ``thin`` (the same at ``q0 h = 0.1``, where ``max |W|/K``
   reaches 15 at friction 1), and ``plate`` (a remote-pressure layer at ``q0 h = 0.1``, ``--nu``: plate-like,
   the semismooth solver with the long-wave coarse space). Each scene gets its own mean pressure per contact fraction.
2. **layer**: frictionless, at the half-space scene's surface and load (``--nu``): a confined layer
   at ``q0 h = 1`` and a thick one (``--thick-q0h`` 20) that :func:`contactlib.model.bodies.body_model`
   must reduce to the half-space (``attrs['body']``), over the half-space solve.
3. **cm**: the ``q0 h = 1`` confined layer of measurement 2 (2D, ``--cm-sizes``) against
   ContactMechanics' ``PeriodicFFTElasticHalfSpace(thickness=...)`` and its Polonsky-Keer solver
   (``make_system(...).minimize_proxy``) at equal or better accuracy: pressure error (relative L2)
   against contactlib at ``--ref-tol``; ContactMechanics' tolerance is tightened by half decades
   until its error is no larger than contactlib's at ``--tol``. Contact sets are compared node by
   node.

Timing (all measurements): each configuration is solved once as a warm-up (FFTW plans are cached
per shape, so planning is excluded), then ``--repeats`` times (more, up to 15, when that would
take less than ``--min-time`` seconds in all); the median is reported, both of the whole
``contactlib.solve`` call and of the solver's own ``attrs['wall_time']`` (set-up and labelling
excluded). The configurations compared in one row (a scene without and with friction; the
half-space and its layers) are timed interleaved, one solve of each in turn, so that a change in
the machine's load hits them alike. A ContactMechanics solve longer than ``--single-above`` seconds
is timed once (the ladder's own run).

Iteration counts of the 1D profiles are sensitive to round-off: a change of the last digits of the
load, or the uniform compression that a thick confined layer keeps when it is reduced to the
half-space, moves them by up to +-30 % (the answer does not move). The per-iteration columns
separate that from the cost of an iteration.

Run ``python -m benchmarks.bench_friction --help``.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

import contactlib

from .common import (calibrate_load, dist_version, host_info, ladder, rel_l2, self_affine_surface,
                     write_json as write_payload)
from .peers import ContactMechanicsPeer, contactmechanics_solve

MAX_REPEATS = 15
"""Most timed solves of one configuration (reached only by solves far shorter than ``--min-time``)."""

SCENES = {
    # name: (Poisson ratio option, q0 h or None for the half-space, what couples)
    "half-space": ("nu", None, "material"),
    "confined": ("layer_nu", 1.0, "geometric"),
    "thin": ("layer_nu", 0.1, "geometric"),
    "plate": ("nu", 0.1, "geometric"),  # a remote-pressure layer (free back face): plate-like at long waves
}
BASES = {"plate": "remote_pressure"}
"""The layer base of a scene (default confined)."""


# ----------------------------------------------------------------------------------- solving

def thickness_for(q0h: float, length: float = 1.0) -> float:
    """Layer thickness of ``q0 h`` on a window of ``length``: ``q0 = 2 pi / length``."""
    return q0h * length / (2 * math.pi)


def solve_once(heights, *, p, nu, q0h, mu, tol, args, max_iter=10_000, base="confined") -> tuple[dict, object]:
    """One ``contactlib.solve``: its summary and the dataset (the partial one when it did not converge)."""
    layer = None if q0h is None else contactlib.Layer(thickness_for(q0h), base=base)
    t0 = time.perf_counter()
    converged = True
    try:
        out = contactlib.solve(heights, E=args.E, nu=nu, mean_pressure=p, tol=tol, layer=layer, friction=mu,
                               sliding_direction=0.0, max_iter=max_iter)
    except contactlib.ConvergenceError as exc:
        out, converged = exc.dataset, False
    call = time.perf_counter() - t0
    return {
        "call_s": call, "wall_s": float(out.attrs["wall_time"]), "iterations": int(out.iterations),
        "outer_iterations": int(out.get("outer_iterations", 0)), "contact_area": float(out.contact_area),
        "residual": float(out.residual), "converged": converged, "model": str(out.attrs["model"]),
        "body": str(out.attrs.get("body", "?")), "coupling": str(out.attrs.get("coupling", "?")),
    }, out


class Bench:
    """Calibrated loads and timed configurations, cached: measurement 2 reuses measurement 1's
    half-space solves, measurement 3 measurement 2's layer solves."""

    def __init__(self, args, log):
        self.args, self.log = args, log
        self.surfaces, self.loads, self.timed = {}, {}, {}

    def surface(self, dim: int, n: int):
        if (dim, n) not in self.surfaces:
            self.surfaces[dim, n] = self_affine_surface(n, self.args, dim=dim)
        return self.surfaces[dim, n]

    def load(self, dim: int, n: int, nu: float, q0h, target: float, base: str = "confined") -> tuple[float, float]:
        """Mean pressure giving contact fraction ``target`` (within ``--calibration-rtol``) on the
        frictionless scene: secant on log A against log p over loose solves."""
        key = (dim, n, nu, q0h, target, base)
        if key in self.loads:
            return self.loads[key]
        a, heights = self.args, self.surface(dim, n)
        E_star = a.E / (1 - nu**2)
        p = target * E_star * a.rms_slope / 2  # A ~ 2 p / (E* h'_rms) on a half-space at small contact

        def area(p):
            return solve_once(heights, p=p, nu=nu, q0h=q0h, mu=0.0, tol=a.calibration_tol, args=a,
                              base=base)[0]["contact_area"]

        p, A = calibrate_load(area, target, p, rtol=a.calibration_rtol, steps=a.calibration_steps)
        self.loads[key] = (p, A)
        return p, A

    def measure(self, dim, n, configs: list[dict], *, reuse: bool = False) -> list[dict]:
        """Median times of several configurations (``dict(p=, nu=, q0h=, mu=)``) on one surface, timed
        interleaved (one solve of each in turn, ``repeats`` rounds) after one warm-up solve of each, so
        that a change of the machine's load hits all of them alike. ``reuse``: take a configuration
        measured before from the cache (measurement 3 reuses measurement 2's layer)."""
        a = self.args
        keys = [(dim, n, c["p"], c["nu"], c["q0h"], c["mu"], a.tol, c.get("base", "confined")) for c in configs]
        if reuse and all(k in self.timed for k in keys):
            return [self.timed[k] for k in keys]
        heights = self.surface(dim, n)
        warm = [solve_once(heights, **c, tol=a.tol, args=a)[0] for c in configs]
        slowest = max(w["call_s"] for w in warm)
        reps = max(a.repeats, min(MAX_REPEATS, math.ceil(a.min_time / max(slowest, 1e-6))))
        runs = [[] for _ in configs]
        for _ in range(reps):
            for i, c in enumerate(configs):
                runs[i].append(solve_once(heights, **c, tol=a.tol, args=a)[0])
        out = []
        for key, c, w, rs in zip(keys, configs, warm, runs):
            res = dict(rs[-1], call_s=float(np.median([r["call_s"] for r in rs])),
                       wall_s=float(np.median([r["wall_s"] for r in rs])),
                       calls_s=[r["call_s"] for r in rs], walls_s=[r["wall_s"] for r in rs], repeats=reps,
                       converged=all(r["converged"] for r in rs), warmup_call_s=w["call_s"],
                       iterations_all_equal=len({r["iterations"] for r in rs}) == 1)
            self.timed[key] = res
            out.append(res)
            self.log(f"    {dim}D N={n} nu={c['nu']} q0h={c['q0h']} {c.get('base', '')} mu={c['mu']} p={c['p']:.5g}: {res['call_s']:.4f} s "
                     f"(solver {res['wall_s']:.4f} s, x{reps}), {res['iterations']} it / {res['outer_iterations']} "
                     f"outer, A={res['contact_area']:.4f}{'' if res['converged'] else ' NOT CONVERGED'}")
        return out


def per_iteration_ratio(m: dict, base: dict) -> float:
    """Solver time per (inner) iteration of ``m`` over that of ``base``."""
    return (m["wall_s"] / max(m["iterations"], 1)) / (base["wall_s"] / max(base["iterations"], 1))


def cases(args):
    return [(1, n) for n in args.sizes_1d] + [(2, n) for n in args.sizes_2d]


def scene_nu(args, scene: str) -> float:
    return getattr(args, SCENES[scene][0])


# ------------------------------------------------------------------------ 1. friction

def bench_friction(bench: Bench) -> list[dict]:
    args, rows = bench.args, []
    for dim, n in cases(args):
        for scene in args.scenes:
            nu, q0h = scene_nu(args, scene), SCENES[scene][1]
            for target in args.contact:
                layer_base = BASES.get(scene, "confined")
                p, a_cal = bench.load(dim, n, nu, q0h, target, layer_base)
                base, *coupled = bench.measure(dim, n, [dict(p=p, nu=nu, q0h=q0h, mu=mu, base=layer_base)
                                                        for mu in [0.0] + list(args.frictions)])
                for mu, m in zip(args.frictions, coupled):
                    rows.append({
                        "dim": dim, "n": n, "scene": scene, "coupling_kind": SCENES[scene][2], "nu": nu, "q0h": q0h,
                        "target_area": target, "mean_pressure": p, "friction": mu,
                        "frictionless": base, "frictional": m,
                        "ratio_call": m["call_s"] / base["call_s"], "ratio_wall": m["wall_s"] / base["wall_s"],
                        "iteration_ratio": m["iterations"] / max(base["iterations"], 1),
                        "per_iteration_ratio": per_iteration_ratio(m, base),
                    })
    return rows


def table_friction(rows, args) -> list[str]:
    out = ["## 1. Coupled over frictionless (same scene, surface, load, tol)", "",
           f"Target: ratio <= {args.friction_target:g}; `!` marks a ratio above it, `NC` a solve that did not "
           "converge. "
           "it0: iterations of the frictionless solve; it (outer): inner iterations summed over the outer "
           "(Anderson) iterations of the coupled solve; t = median of the whole `solve` call, t_solver = "
           "median of `attrs['wall_time']`; ratio = t_mu / t_0 (call), ratio_solver = the same of t_solver = "
           "it ratio (inner iterations over it0) x per-it (solver time per inner iteration over the frictionless "
           "one: the outer loop's own work, W p, Anderson mixing, restarts of the inner solve).", "",
           "| dim | N | scene | nu | q0 h | A target | p | mu | model | it0 | it (outer) | A0 | A_mu | t0 [s] "
           "| t_mu [s] "
           "| ratio | ratio_solver | it ratio | per-it |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        b, m = r["frictionless"], r["frictional"]
        flag = " !" if r["ratio_call"] > args.friction_target else ""
        nc = "" if (b["converged"] and m["converged"]) else " NC"
        model = m["body"] + (", coupled" if m["coupling"] != "none" else ", uncoupled")
        q0h = "-" if r["q0h"] is None else f"{r['q0h']:g}"
        out.append(
            f"| {r['dim']}D | {r['n']} | {r['scene']} | {r['nu']:g} | {q0h} "
            f"| {r['target_area']:g} | {r['mean_pressure']:.4g} | {r['friction']:g} | {model} | {b['iterations']} "
            f"| {m['iterations']} ({m['outer_iterations']}) | {b['contact_area']:.4f} | {m['contact_area']:.4f} "
            f"| {b['call_s']:.4f} | {m['call_s']:.4f} | {r['ratio_call']:.2f}{flag}{nc} | {r['ratio_wall']:.2f} "
            f"| {r['iteration_ratio']:.2f} | {r['per_iteration_ratio']:.2f} |")
    return out


# ----------------------------------------------------------------------------- 2. layer

def bench_layer(bench: Bench) -> list[dict]:
    args, rows = bench.args, []
    nu = args.nu
    for dim, n in cases(args):
        for target in args.contact:
            p, _ = bench.load(dim, n, nu, None, target)
            q0hs = (args.layer_q0h, args.thick_q0h)
            half, *layers = bench.measure(dim, n, [dict(p=p, nu=nu, q0h=q0h, mu=0.0) for q0h in (None,) + q0hs])
            for q0h, m in zip(q0hs, layers):
                rows.append({"dim": dim, "n": n, "nu": nu, "q0h": q0h, "thickness": thickness_for(q0h),
                             "target_area": target, "mean_pressure": p, "halfspace": half, "layer": m,
                             "reduced_to_halfspace": m["body"] == "half-space",
                             "ratio_call": m["call_s"] / half["call_s"], "ratio_wall": m["wall_s"] / half["wall_s"],
                             "per_iteration_ratio": per_iteration_ratio(m, half)})
    return rows


def table_layer(rows, args) -> list[str]:
    out = ["## 2. Confined layer over half-space (frictionless, same surface and load)", "",
           f"Target: ratio <= {args.layer_target:g} (`!` above it). The load is the half-space's for the target "
           "contact fraction; the layer is stiffer, so its contact is smaller and its iteration count differs. "
           f"body: `attrs['body']` (the q0 h = {args.thick_q0h:g} layer must be reduced to the half-space). "
           "t: median of the whole call; t_solver: of `attrs['wall_time']`; per-it: solver time per iteration, "
           "layer over half-space (the three bodies are timed interleaved).", "",
           "| dim | N | nu | A target | p | q0 h | body | it half | it layer | A half | A layer | t half [s] | "
           "t layer [s] | ratio | ratio_solver | per-it |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        h, m = r["halfspace"], r["layer"]
        flag = " !" if r["ratio_call"] > args.layer_target else ""
        nc = "" if (h["converged"] and m["converged"]) else " NC"
        out.append(
            f"| {r['dim']}D | {r['n']} | {r['nu']:g} | {r['target_area']:g} | {r['mean_pressure']:.4g} | {r['q0h']:g} "
            f"| {m['body']} | {h['iterations']} | {m['iterations']} | {h['contact_area']:.4f} "
            f"| {m['contact_area']:.4f} "
            f"| {h['call_s']:.4f} | {m['call_s']:.4f} | {r['ratio_call']:.2f}{flag}{nc} | {r['ratio_wall']:.2f} "
            f"| {r['per_iteration_ratio']:.2f} |")
    return out


# ------------------------------------------------------------------------ 3. ContactMechanics

def kernel_difference(cm_green: np.ndarray, n: int, E: float, nu: float, thickness: float) -> float:
    """Largest relative difference between ContactMechanics' Green's function (its muGrid layout is
    the transpose of numpy's rfft2) and contactlib's layer compliance, ``q = 0`` included."""
    from contactlib.core.grid import Grid
    from contactlib.kernels.tensor import surface_green_tensor

    ours = surface_green_tensor(Grid((n, n), (1.0, 1.0)), E, nu, thickness, "confined").normal
    theirs = cm_green.real if cm_green.shape == ours.shape else cm_green.real.T
    return float(np.max(np.abs(theirs / ours - 1)))


def bench_cm(bench: Bench) -> list[dict]:
    args, rows = bench.args, []
    nu, q0h = args.nu, args.layer_q0h
    th = thickness_for(q0h)
    for n in args.cm_sizes:
        heights = bench.surface(2, n)
        h = np.ascontiguousarray(heights.transpose("x", "y").values)  # [ix, iy], as the peer indexes it
        for target in args.contact:
            p, _ = bench.load(2, n, nu, None, target)  # the half-space's load, as in measurement 2
            ours, = bench.measure(2, n, [dict(p=p, nu=nu, q0h=q0h, mu=0.0)], reuse=True)
            _, out = solve_once(heights, p=p, nu=nu, q0h=q0h, mu=0.0, tol=args.tol, args=args)
            _, ref = solve_once(heights, p=p, nu=nu, q0h=q0h, mu=0.0, tol=args.ref_tol, args=args, max_iter=3000)
            p_ours, p_ref = out.pressure.values, ref.pressure.values
            err_ours = rel_l2(p_ours, p_ref)
            bench.log(f"    CM N={n} A={target}: contactlib {ours['call_s']:.3f} s, error {err_ours:.2e} "
                      f"(reference residual {float(ref.residual):.1e})")
            steps, chosen, last = [], None, None
            for tol in ladder(max(err_ours, 1e-14)):
                last = contactmechanics_solve(h, mean_pressure=p, E=args.E, nu=nu, thickness=th, tol=tol,
                                              max_iter=args.cm_max_iter)
                e = rel_l2(last["pressure"], p_ref)
                steps.append({"tol": tol, "pressure_error": e, "iterations": last["iterations"],
                              "time_s": last["seconds"], "converged": last["converged"]})
                bench.log(f"    CM tol {tol:.1e}: error {e:.2e}, {last['iterations']} it, {last['seconds']:.2f} s")
                if e <= err_ours:
                    chosen = tol
                    break
                if not last["converged"] or len(steps) >= args.max_ladder:
                    break
            if chosen is None:
                chosen = steps[-1]["tol"]
                bench.log(f"    CM: no tolerance on the ladder reached error {err_ours:.2e}; using the tightest tried")
            times = [last["seconds"]]
            if last["seconds"] <= args.single_above:
                for _ in range(args.repeats - 1):
                    again = contactmechanics_solve(h, mean_pressure=p, E=args.E, nu=nu, thickness=th, tol=chosen,
                                                   max_iter=args.cm_max_iter)
                    times.append(again["seconds"])
            t_cm = float(np.median(times))
            c_ours, c_cm, c_ref = p_ours > 0, last["pressure"] > 0, p_ref > 0
            a_ours, a_cm = c_ours.mean(), c_cm.mean()
            rows.append({
                "n": n, "nu": nu, "q0h": q0h, "thickness": th, "target_area": target, "mean_pressure": p,
                "contactlib": {"tol": args.tol, "iterations": ours["iterations"], "call_s": ours["call_s"],
                               "wall_s": ours["wall_s"], "pressure_error": err_ours, "contact_area": float(a_ours),
                               "body": ours["body"], "converged": ours["converged"]},
                "reference": {"tol": args.ref_tol, "iterations": int(ref.iterations), "residual": float(ref.residual),
                              "contact_area": float(c_ref.mean())},
                "cm": {"tol": chosen, "iterations": last["iterations"], "time_s": t_cm, "times_s": times,
                       "pressure_error": rel_l2(last["pressure"], p_ref), "contact_area": float(a_cm),
                       "converged": last["converged"], "ladder": steps},
                "area_rel_diff": float((a_ours - a_cm) / a_cm),
                "nodes_only_contactlib": int(np.count_nonzero(c_ours & ~c_cm)),
                "nodes_only_cm": int(np.count_nonzero(c_cm & ~c_ours)),
                "nodes_differing_contactlib_vs_ref": int(np.count_nonzero(c_ours != c_ref)),
                "nodes_differing_cm_vs_ref": int(np.count_nonzero(c_cm != c_ref)),
                "pressure_rel_l2_contactlib_vs_cm": rel_l2(p_ours, last["pressure"]),
                "kernel_max_rel_diff": kernel_difference(last["greens_function"], n, args.E, nu, th),
                "ratio": ours["call_s"] / t_cm, "ratio_solver": ours["wall_s"] / t_cm,
            })
            bench.log(f"    CM: {t_cm:.3f} s at tol {chosen:.1e}; ratio contactlib/CM {rows[-1]['ratio']:.3f}; "
                      f"nodes differing {rows[-1]['nodes_only_contactlib']}+{rows[-1]['nodes_only_cm']}")
    return rows


def table_cm(rows, args) -> list[str]:
    out = [f"## 3. Confined layer (q0 h = {args.layer_q0h:g}, nu = {args.nu:g}) against ContactMechanics", "",
           "Same surface and load (the half-space's of measurement 2). error: pressure rel. L2 against contactlib "
           "at tol "
           f"{args.ref_tol:g}; ContactMechanics' tol tightened by half decades until its error <= contactlib's at tol "
           f"{args.tol:g}. nodes: contact nodes in contactlib's set only / in ContactMechanics' only; vs ref: nodes "
           "whose contact state differs from the reference's (contactlib, CM). dp L2 = |p_ours - p_CM| / |p_CM|. "
           "kernel: largest relative difference of the two Green's functions on the grid (q = 0 included). "
           f"ratio = t_contactlib (whole call) / t_CM (substrate set-up + solve), target <= {args.cm_target:g}.", "",
           "| N | A target | p | ours it | ours error | ours t [s] | CM tol | CM it | CM error | CM t [s] | A ours "
           "| A CM "
           "| dA rel | nodes | vs ref | dp L2 | kernel | ratio | ratio_solver |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        o, c = r["contactlib"], r["cm"]
        flag = " !" if r["ratio"] > args.cm_target else ""
        out.append(
            f"| {r['n']} | {r['target_area']:g} | {r['mean_pressure']:.4g} | {o['iterations']} "
            f"| {o['pressure_error']:.1e} "
            f"| {o['call_s']:.3f} | {c['tol']:.1e} | {c['iterations']}{'' if c['converged'] else ' NC'} "
            f"| {c['pressure_error']:.1e} | {c['time_s']:.3f} | {o['contact_area']:.6f} | {c['contact_area']:.6f} "
            f"| {r['area_rel_diff']:.1e} | {r['nodes_only_contactlib']} / {r['nodes_only_cm']} "
            f"| {r['nodes_differing_contactlib_vs_ref']}, {r['nodes_differing_cm_vs_ref']} "
            f"| {r['pressure_rel_l2_contactlib_vs_cm']:.1e} | {r['kernel_max_rel_diff']:.0e} | {r['ratio']:.3f}{flag} "
            f"| {r['ratio_solver']:.3f} |")
    return out


# ------------------------------------------------------------------------------------ driver

def machine_info(args) -> dict:
    info = host_info()
    if "cm" in args.measurements and not args.skip_cm:
        info["ContactMechanics"] = dist_version("ContactMechanics")
        info["SurfaceTopography"] = dist_version("SurfaceTopography")
        info["muGrid"] = dist_version("muGrid")
    return info


def markdown(results: dict, info: dict, args) -> str:
    out = ["# contactlib friction and layer benchmark", ""]
    out += [f"- {k}: {v}" for k, v in info.items()]
    out += [f"- surface: self_affine(N, hurst={args.hurst}, q_roll={args.q_roll}, q_cutoff={args.cutoff_fraction}*N, "
            f"rms_slope={args.rms_slope}, seed={args.seed}, dim=1 or 2) on the unit window (q0 = 2 pi); E={args.E}; "
            f"tol={args.tol:g}; loads calibrated per scene on frictionless solves at tol {args.calibration_tol:g} "
            f"(contact within {100 * args.calibration_rtol:g} % of the target or {args.calibration_steps} secant "
            "steps)",
            f"- time: median of {args.repeats} solves (more, up to {MAX_REPEATS}, when they take under "
            f"{args.min_time:g} s in all) after one warm-up solve of each configuration; the configurations "
            "compared in one row (frictionless and frictional; half-space and layers) are timed interleaved", ""]
    for name, table in (("friction", table_friction), ("layer", table_layer), ("cm", table_cm)):
        if results.get(name):
            out += table(results[name], args) + [""]
    return "\n".join(out)


def write_json(path: Path, info: dict, args, results: dict) -> None:
    write_payload(path, {"machine": info, "args": {k: (str(v) if isinstance(v, Path) else v)
                                                   for k, v in vars(args).items()}, **results})


def parse(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes-1d", type=int, nargs="*", default=[2**14, 2**15, 2**16], help="profile lengths")
    ap.add_argument("--sizes-2d", type=int, nargs="*", default=[512, 1024], help="N of the N x N surfaces")
    ap.add_argument("--cm-sizes", type=int, nargs="*", default=[512],
                    help="N of the 2D surfaces compared with ContactMechanics (about 5-15 s a solve at 512, "
                         "35-160 s at 1024 here)")
    ap.add_argument("--contact", type=float, nargs="+", default=[0.1, 0.5], help="target contact fractions")
    ap.add_argument("--measurements", nargs="+", default=["friction", "layer", "cm"],
                    choices=["friction", "layer", "cm"])
    ap.add_argument("--scenes", nargs="+", default=["half-space", "confined"], choices=sorted(SCENES),
                    help="scenes of measurement 1 ('thin': q0 h = 0.1, slow: many outer iterations)")
    ap.add_argument("--frictions", type=float, nargs="+", default=[0.5, 1.0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--min-time", type=float, default=0.5,
                    help="time a configuration more than --repeats times (at most 15) while its solves take less "
                         "than this many seconds in all")
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--ref-tol", type=float, default=1e-12, help="contactlib's reference for the comparison with CM")
    ap.add_argument("--calibration-tol", type=float, default=1e-5)
    ap.add_argument("--calibration-rtol", type=float, default=0.03)
    ap.add_argument("--calibration-steps", type=int, default=6)
    ap.add_argument("--nu", type=float, default=0.3, help="half-space scene, measurement 2 and the CM comparison")
    ap.add_argument("--layer-nu", type=float, default=0.5, help="the layer scenes of measurement 1")
    ap.add_argument("--layer-q0h", type=float, default=1.0, help="q0 h of measurements 2 and 3")
    ap.add_argument("--thick-q0h", type=float, default=20.0,
                    help="q0 h of the layer that must reduce to the half-space")
    ap.add_argument("--E", type=float, default=1.0)
    ap.add_argument("--hurst", type=float, default=0.8)
    ap.add_argument("--q-roll", type=float, default=4.0)
    ap.add_argument("--cutoff-fraction", type=float, default=1 / 8, help="q_cutoff = fraction * N")
    ap.add_argument("--rms-slope", type=float, default=0.1)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--skip-cm", action="store_true", help="leave out measurement 3")
    ap.add_argument("--cm-max-iter", type=int, default=100_000)
    ap.add_argument("--max-ladder", type=int, default=6, help="most tolerances tried for ContactMechanics")
    ap.add_argument("--single-above", type=float, default=30.0,
                    help="a ContactMechanics solve longer than this is timed once (the ladder's own run)")
    ap.add_argument("--friction-target", type=float, default=3.0)
    ap.add_argument("--layer-target", type=float, default=1.2)
    ap.add_argument("--cm-target", type=float, default=0.1)
    ap.add_argument("--json", type=Path, help="also write every number here")
    ap.add_argument("--quiet", action="store_true", help="no progress on stderr")
    return ap.parse_args(argv)


def main(argv=None) -> int:
    args = parse(argv)

    def log(msg):
        if not args.quiet:
            print(msg, file=sys.stderr, flush=True)

    info = machine_info(args)
    bench, results = Bench(args, log), {}
    steps = [("friction", bench_friction), ("layer", bench_layer)]
    if not args.skip_cm:
        if ContactMechanicsPeer.available():
            steps.append(("cm", bench_cm))
        else:
            log("ContactMechanics / SurfaceTopography not importable: measurement 3 skipped")
    for name, run in steps:
        if name in args.measurements:
            log(f"measurement {name}")
            t0 = time.perf_counter()
            results[name] = run(bench)
            log(f"  ({time.perf_counter() - t0:.0f} s)")
            if args.json:  # after every measurement: a killed run keeps what it measured
                write_json(args.json, info, args, results)
    print(markdown(results, info, args))
    if args.json:
        write_json(args.json, info, args, results)
    return 0


if __name__ == "__main__":
    sys.exit(main())
