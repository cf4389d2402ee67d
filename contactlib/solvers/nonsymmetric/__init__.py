"""Solvers of contact problems whose operator has a skew part (Coulomb friction's normal-tangential coupling,
steady viscoelastic sliding): semismooth GMRES on the contact set (:mod:`.krylov`, its sweeps :mod:`.sweeps` and
recycled Krylov vectors :mod:`.recycle`), Douglas-Rachford splitting (:mod:`.splitting`) and the coupled fixed
point (:mod:`.coupled`); :mod:`.choice` says which one runs, and which finishes another."""
