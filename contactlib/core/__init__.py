"""The vocabulary every other part speaks: the grid and its wavevectors (:mod:`.grid`), the one FFT convention
(:mod:`.fft`), input validation that names the parameter (:mod:`.inputs`), the labels of every output variable
(:mod:`.labels`) and the compiled-loop helpers (:mod:`._numba`). Imports numpy, scipy, pyfftw, numba and xarray
only, never another part of contactlib."""
