"""The lowest layer, importing nothing of the project: errors and warnings
(:mod:`~dcfpb.common.errors`), constants and unit factors (:mod:`~dcfpb.common.units`),
parameter checks with their one error template (:mod:`~dcfpb.common.validation`), lazy
package exports (:mod:`~dcfpb.common.lazy`) and atomic output files
(:mod:`~dcfpb.common.files`)."""
