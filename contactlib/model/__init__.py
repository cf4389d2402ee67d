"""The physical model of a scene, as data: materials (:mod:`.materials`: elastic, Prony-series viscoelastic), the
body and its operators on the grid (:mod:`.bodies`: half-space or layer, the Green's tensor's normal, coupling and
viscoelastic parts; :mod:`.operators`: a kernel applied by FFT, periodic or zero-padded), the interface laws
(:mod:`.adhesion`) and the hereditary integral's state (:mod:`.hereditary`). Imports :mod:`contactlib.core` and
:mod:`contactlib.kernels`."""
