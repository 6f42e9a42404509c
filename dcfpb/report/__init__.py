"""Reports: documents written from an analysis's result objects, beside the command line at the
top of the layers (presentation: they compute nothing of their own). :mod:`~dcfpb.report.design`
writes the folder of ``dcfpb design`` (a Chapter 17 analysis: Markdown, HTML, JSON, CSV and the
figures of :mod:`dcfpb.plotting.design`)."""
