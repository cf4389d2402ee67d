"""Problems and the drivers of their paths: the validated scene (:mod:`.scene`), the prepared problem
(:mod:`.problem`: :func:`contactlib.prepare`, :class:`contactlib.Problem`) and :func:`contactlib.solve` on it
(:mod:`.contact`), the adhesive scene (:mod:`.adhesive`, :mod:`.adhesive_choice`), and the paths: a target contact
area (:mod:`.area_target`), speeds (:mod:`.speed_path`), time (:mod:`.transient`, :mod:`.reciprocating`) and
loading-unloading (:mod:`.adhesion_curve`). May import every part below it (core, kernels, model, solvers, analysis)
and the checks (:mod:`contactlib.invariants`, :mod:`contactlib.resolution`, :mod:`contactlib.accuracy`)."""
