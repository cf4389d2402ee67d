"""Command line: ``contactlib surface`` and ``contactlib solve`` (surface files in, NetCDF out)."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import xarray as xr

from . import surfaces
from ._version import __version__
from .model.bodies import Layer
from .problems.contact import ConvergenceError, solve
from .distributed.launch import launched_ranks


def _write(ds: xr.Dataset | xr.DataArray, path: str) -> None:
    import os

    tmp = f"{path}.tmp{os.getpid()}"
    ds.to_netcdf(tmp)
    os.replace(tmp, path)  # never leave a partial file under the final name


def _surface(args) -> int:
    if launched_ranks() > 1:  # under mpirun: each rank generates and writes its rows
        from .distributed import cli as distributed_cli

        return distributed_cli.surface(args, _synthetic_length)
    if args.source is not None:
        h = _read(args, args.source, args.detrend or "plane")
    else:
        missing = [f"--{k.replace('_', '-')}" for k in ("n", "hurst", "q_roll", "q_cutoff") if getattr(args, k) is None]
        if missing or (args.rms_height is None) == (args.rms_slope is None):
            raise ValueError(f"a synthetic surface needs {', '.join(missing) or 'exactly one of'} "
                             f"{'and one of ' if missing else ''}--rms-height or --rms-slope (or --from FILE)")
        h = surfaces.self_affine(
            args.n, length=_synthetic_length(args.length), hurst=args.hurst, q_low=args.q_low,
            q_roll=args.q_roll, q_cutoff=args.q_cutoff, rms_height=args.rms_height, rms_slope=args.rms_slope,
            seed=args.seed, dim=args.dim, anisotropy=args.anisotropy, angle=args.angle,
        )
    h.attrs["command"] = " ".join(sys.argv)
    _write(h.to_dataset(), args.output)
    return 0


def _synthetic_length(length) -> float:
    if length is None:
        return 1.0
    if len(length) != 1:
        raise ValueError(f"--length: a synthetic surface is square, give one value, got {length}")
    return length[0]


def _read(args, path: str, detrend: str) -> xr.DataArray:
    """A surface file through :func:`contactlib.surfaces.read` with the command line's options."""
    length = None if args.length is None else (args.length[0] if len(args.length) == 1 else args.length)
    return surfaces.read(path, length=length, unit=args.unit, periodic=args.periodic, detrend=detrend,
                         fill=args.fill, format=args.format)


def _solve(args) -> int:
    if launched_ranks() > 1:  # under mpirun: a distributed solve, each rank holding its rows
        from .distributed import cli as distributed_cli

        return distributed_cli.solve(args)
    if args.variable != "height":  # another variable of a NetCDF file, taken as it is
        with xr.open_dataset(args.surface) as ds:
            heights = ds[args.variable].load()
    else:  # a .nc file is a prepared surface (contactlib's): not detrended again unless asked
        default = "none" if Path(args.surface).suffix.lower() in (".nc", ".nc4", ".cdf") else "plane"
        heights = _read(args, args.surface, args.detrend or default)
    try:
        layer = None if args.thickness is None else Layer(args.thickness, args.base)
        out = solve(
            heights, E=args.E, nu=args.nu, mean_pressure=args.mean_pressure, penetration=args.penetration,
            periodic=args.periodic, tol=args.tol, max_iter=args.max_iter, kernel=args.kernel,
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


def _file_options(parser: argparse.ArgumentParser, length_help: str, detrend_help: str) -> None:
    """Options of a surface file: size, unit, periodicity, preparation (contactlib.surfaces.read)."""
    parser.add_argument("--length", type=float, nargs="+", help=length_help + " (one value, or one per axis)")
    parser.add_argument("--unit", help="length unit of the file's heights and of --length (m, mm, um, nm, ...)")
    periodic = parser.add_mutually_exclusive_group()
    periodic.add_argument("--periodic", dest="periodic", action="store_const", const=True, default=None,
                          help="the window is one period of a periodic surface")
    periodic.add_argument("--non-periodic", dest="periodic", action="store_const", const=False,
                          help="isolated window (zero padding); default: what the file says, else non-periodic")
    parser.add_argument("--detrend", choices=("plane", "line", "mean", "none"), help=detrend_help)
    parser.add_argument("--fill", choices=("interpolate", "mean"), help="fill missing (NaN) heights (default: refuse)")
    parser.add_argument("--format", help="force the file format (netcdf, npy, matrix, xyz, or a SurfaceTopography id)")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="contactlib", description="Rough-surface contact mechanics.")
    parser.add_argument("--version", action="version", version=f"contactlib {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)

    s = sub.add_parser("surface", help="generate a self-affine rough surface, or read a measured one (NetCDF)",
                       description="Gaussian self-affine surface (wavenumbers in multiples of 2 pi / length), or "
                                   "--from FILE: a measured topography as the labelled NetCDF.")
    s.add_argument("--from", dest="source", metavar="FILE",
                   help="read this topography file instead (see contactlib.surfaces.read for the formats)")
    s.add_argument("--n", type=int, help="points per side")
    s.add_argument("--hurst", type=float, help="Hurst exponent in (0, 1]")
    s.add_argument("--q-low", type=float, default=1, help="lowest wavenumber / q0 (default 1)")
    s.add_argument("--q-roll", type=float, help="roll-off wavenumber / q0")
    s.add_argument("--q-cutoff", type=float, help="cutoff wavenumber / q0 (<= n/2)")
    _file_options(s, "window size [m] (default 1); with --from, in --unit, needed where the file lacks it",
                  "detrending of --from FILE (default plane)")
    norm = s.add_mutually_exclusive_group()
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
    v.add_argument("surface", help="surface file: contactlib NetCDF or any format contactlib.surfaces.read reads")
    v.add_argument("--variable", default="height", help="height variable name (default 'height')")
    v.add_argument("--E", type=float, required=True, help="Young's modulus [Pa]")
    v.add_argument("--nu", type=float, required=True, help="Poisson ratio in (-1, 0.5]")
    load = v.add_mutually_exclusive_group(required=True)
    load.add_argument("--mean-pressure", type=float, help="mean pressure over the window [Pa]")
    load.add_argument("--penetration", type=float, help="rigid approach from first contact [m]")
    _file_options(v, "window size in --unit, where the file lacks it", "detrending (default: none for a .nc "
                  "file, a prepared surface; plane otherwise)")
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
    except (ValueError, FileNotFoundError) as err:
        print(f"contactlib {args.command}: error: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    raise SystemExit(main())
