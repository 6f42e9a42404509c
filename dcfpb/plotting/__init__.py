"""Figures for the command line: hysteresis loops, temperature and response histories, floor
spectra, suite distributions.

matplotlib is imported inside each function (Agg backend) so the library runs without it.

Modules: :mod:`~dcfpb.plotting.base` (pyplot, margins, colours), :mod:`~dcfpb.plotting.bearing`
(a bearing test), :mod:`~dcfpb.plotting.building` (building runs),
:mod:`~dcfpb.plotting.spectra` (floor spectra, isolation effect), :mod:`~dcfpb.plotting.suite`
(suite distributions).
"""

from dcfpb.plotting.bearing import plot_bearing_test
from dcfpb.plotting.building import plot_runs
from dcfpb.plotting.spectra import plot_floor_spectra, plot_isolation_effect

__all__ = ["plot_bearing_test", "plot_floor_spectra", "plot_isolation_effect", "plot_runs"]
