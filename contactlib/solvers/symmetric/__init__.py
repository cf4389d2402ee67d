"""Solvers of the symmetric positive (semi-)definite contact problem (the frictionless elastic body):
Polonsky-Keer constrained conjugate gradients (:mod:`.ccg`) and its compiled sweeps (:mod:`.fused`), its dual under
periodic displacement control (:mod:`.dual`), semismooth Newton for plates (:mod:`.semismooth`, with the coarse
correction of :mod:`.coarse`), the seed's active set (:mod:`.active_set`); :mod:`.choice` says which one runs."""
