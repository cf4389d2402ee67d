"""What the figure scripts share: a curve of the mean over seeds with the standard deviation as a band.
(Snakemake puts this folder on the scripts' path.)"""


def band(ax, x, values, dim="seed", **plot_kw):
    """Plot ``values.mean(dim)`` against ``x`` with ``mean +- std`` shaded in the line's colour; the line."""
    mean, std = values.mean(dim), values.std(dim)
    (line,) = ax.plot(x, mean, **{"marker": "o", "ms": 3, **plot_kw})
    ax.fill_between(x, mean - std, mean + std, color=line.get_color(), alpha=0.2, lw=0)
    return line
