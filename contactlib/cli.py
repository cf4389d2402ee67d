"""Command line: ``contactlib surface`` and ``contactlib solve`` (NetCDF in, NetCDF out)."""

from __future__ import annotations

import argparse
import json
import sys

import xarray as xr

from . import surfaces
from ._version import __version__
from .bodies import Layer
from .contact import ConvergenceError, solve


def _write(ds: xr.Dataset | xr.DataArray, path: str) -> None:
    import os

    tmp = f"{path}.tmp{os.getpid()}"
    ds.to_netcdf(tmp)
    os.replace(tmp, path)  # never leave a partial file under the final name


def _surface(args) -> int:
    h = surfaces.self_affine(
        args.n, length=args.length, hurst=args.hurst, q_low=args.q_low, q_roll=args.q_roll,
        q_cutoff=args.q_cutoff, rms_height=args.rms_height, rms_slope=args.rms_slope, seed=args.seed,
        dim=args.dim, anisotropy=args.anisotropy, angle=args.angle,
    )
    h.attrs["command"] = " ".join(sys.argv)
    _write(h.to_dataset(), args.output)
    return 0


def _solve(args) -> int:
    with xr.open_dataset(args.surface) as ds:
        heights = ds[args.variable].load()
    try:
        layer = None if args.thickness is None else Layer(args.thickness, args.base)
        out = solve(
            heights, E=args.E, nu=args.nu, mean_pressure=args.mean_pressure, penetration=args.penetration,
            periodic=not args.non_periodic, tol=args.tol, max_iter=args.max_iter, kernel=args.kernel,
            method=args.method, layer=layer, friction=args.friction, sliding_direction=args.sliding_direction,
        )
        status = 0
    except ConvergenceError as err:
        print(f"contactlib solve: {err}", file=sys.stderr)
        out, status = err.dataset, 3
    out.attrs["source_surface"] = args.surface
    out.attrs["surface_attrs"] = json.dumps({k: str(v) for k, v in heights.attrs.items()})
    _write(out, args.output)
    print(f"contact_area={float(out.contact_area):.6g} mean_pressure={float(out.mean_pressure):.6g} "
          f"penetration={float(out.penetration):.6g} iterations={int(out.iterations)} "
          f"residual={float(out.residual):.3e}"
          + (f" friction_coefficient={float(out.friction_coefficient):.6g}" if "friction_coefficient" in out else ""))
    return status


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="contactlib", description="Rough-surface contact mechanics.")
    parser.add_argument("--version", action="version", version=f"contactlib {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)

    s = sub.add_parser("surface", help="generate a self-affine rough surface (NetCDF)",
                       description="Gaussian self-affine surface; wavenumbers in multiples of 2 pi / length.")
    s.add_argument("--n", type=int, required=True, help="points per side")
    s.add_argument("--length", type=float, default=1.0, help="window size [m] (default 1)")
    s.add_argument("--hurst", type=float, required=True, help="Hurst exponent in (0, 1]")
    s.add_argument("--q-low", type=float, default=1, help="lowest wavenumber / q0 (default 1)")
    s.add_argument("--q-roll", type=float, required=True, help="roll-off wavenumber / q0")
    s.add_argument("--q-cutoff", type=float, required=True, help="cutoff wavenumber / q0 (<= n/2)")
    norm = s.add_mutually_exclusive_group(required=True)
    norm.add_argument("--rms-height", type=float, help="rms height [m]")
    norm.add_argument("--rms-slope", type=float, help="rms slope [1]")
    s.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    s.add_argument("--dim", type=int, default=2, choices=(1, 2), help="1 (profile) or 2 (surface)")
    s.add_argument("--anisotropy", type=float, default=1.0, help="slope-tensor eigenvalue ratio in (0, 1]")
    s.add_argument("--angle", type=float, default=0.0, help="principal direction [rad]")
    s.add_argument("-o", "--output", required=True, help="output NetCDF file")
    s.set_defaults(func=_surface)

    v = sub.add_parser("solve", help="solve frictionless normal contact on a surface file",
                       description="Rigid surface (variable 'height') on an elastic half-space.")
    v.add_argument("surface", help="NetCDF file holding the heights")
    v.add_argument("--variable", default="height", help="height variable name (default 'height')")
    v.add_argument("--E", type=float, required=True, help="Young's modulus [Pa]")
    v.add_argument("--nu", type=float, required=True, help="Poisson ratio in (-1, 0.5]")
    load = v.add_mutually_exclusive_group(required=True)
    load.add_argument("--mean-pressure", type=float, help="mean pressure over the window [Pa]")
    load.add_argument("--penetration", type=float, help="rigid approach from first contact [m]")
    v.add_argument("--non-periodic", action="store_true", help="isolated footprint (zero padding)")
    v.add_argument("--tol", type=float, default=1e-8, help="residual tolerance (default 1e-8)")
    v.add_argument("--max-iter", type=int, default=10_000, help="iteration bound (default 10000)")
    v.add_argument("--kernel", default="spectral", choices=("spectral", "love"))
    v.add_argument("--method", default="cg", choices=("cg", "active-set"))
    v.add_argument("--thickness", type=float, help="layer thickness [m] (default: a half-space)")
    v.add_argument("--base", default="confined", choices=("confined", "remote_pressure"),
                   help="the layer's back face: on a rigid base, or free under the balancing pressure")
    v.add_argument("--friction", type=float, default=0.0, help="Coulomb friction coefficient mu_c (default 0)")
    v.add_argument("--sliding-direction", type=float, default=0.0,
                   help="direction the rigid surface moves relative to the body [rad] (default 0: +x)")
    v.add_argument("-o", "--output", required=True, help="output NetCDF file")
    v.set_defaults(func=_solve)
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except ValueError as err:
        print(f"contactlib {args.command}: error: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    raise SystemExit(main())
