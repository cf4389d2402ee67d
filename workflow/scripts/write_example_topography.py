"""Write a seeded self-affine surface as a plain-text height matrix (one row per y, in the configured unit):
a stand-in for a measured file, so that the measured-surface study runs end to end without external data."""

import sys

import numpy as np

from contactlib import surfaces
from contactlib.surfaces.preparation import METRES_PER

sm = snakemake  # noqa: F821 (injected by Snakemake)
sys.stderr = open(sm.log[0], "w")
spec = dict(sm.params.example)
unit = spec.pop("unit")
length = spec.pop("length")  # [unit]
h = surfaces.self_affine(spec.pop("n"), length=length * METRES_PER[unit], **spec)
np.savetxt(sm.output[0], h.transpose("y", "x").values / METRES_PER[unit], fmt="%.17g",
           header=f"contactlib.surfaces.self_affine {spec}, heights in {unit}, window {length} {unit}, periodic")
print(f"wrote {sm.output[0]}: {h.shape} heights in {unit}", file=sys.stderr)
