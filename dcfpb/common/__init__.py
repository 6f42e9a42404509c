"""What every layer of the project builds on, and which imports nothing of ours: the errors and
warnings (:mod:`~dcfpb.common.errors`), physical constants and unit factors
(:mod:`~dcfpb.common.units`), the parameter checks with their one error template
(:mod:`~dcfpb.common.validation`) and the lazy imports of the packages' public names
(:mod:`~dcfpb.common.lazy`)."""
