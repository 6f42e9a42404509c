"""Figures of the command line: :mod:`~dcfpb.plotting.bearing` (a bearing test's loops and
temperature), :mod:`~dcfpb.plotting.building` and :mod:`~dcfpb.plotting.plan` (building runs),
:mod:`~dcfpb.plotting.spectra` (floor spectra, isolation effect), :mod:`~dcfpb.plotting.suite`
(suite distributions, scaled spectra), on the shared :mod:`~dcfpb.plotting.base`. matplotlib is
imported inside each function (Agg backend), so the library runs without it."""

from dcfpb.plotting.bearing import plot_bearing_test
from dcfpb.plotting.building import plot_runs
from dcfpb.plotting.spectra import plot_floor_spectra, plot_isolation_effect

__all__ = ["plot_bearing_test", "plot_floor_spectra", "plot_isolation_effect", "plot_runs"]
