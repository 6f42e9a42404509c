"""Ground motions: records, readers, units, processing, spectra, scaling and synthetics; every
name in ``__all__`` is importable from the package. Of the project it imports only
`dcfpb.common`.
"""

from groundmotions.bundled import bundled_names, load_bundled
from groundmotions.pairs import GroundMotionPair, read_pair, read_pair_manifest
from groundmotions.pairs.rotd import RotDSpectrum, rotd_spectra
from groundmotions.processing import (
    arias_intensity,
    baseline_corrected,
    filtered,
    resampled,
    significant_duration,
    velocity_and_displacement,
    zero_residuals,
)
from groundmotions.readers import read_peer_at2, read_record, read_text_record
from groundmotions.records import GroundMotion, RecordFormatError
from groundmotions.scaling import (
    ScalingReport,
    TargetSpectrum,
    asce7_design_spectrum,
    isolated_period_range,
    scale_suite,
    suite_spectra,
)
from groundmotions.spectra import (
    Spectrum,
    nigam_jennings_coefficients,
    peak_ground_values,
    response_spectra,
    response_spectrum,
    sdof_response,
    spectrum,
)
from groundmotions.synthetic import (
    PiecewiseEnvelope,
    SaragoniHartEnvelope,
    clough_penzien,
    clough_penzien_psd,
    kanai_tajimi,
    kanai_tajimi_psd,
    synthetic_pair,
)
from groundmotions.units import TO_M_PER_S2, UNIT_NAMES, parse_units

__all__ = [
    "TO_M_PER_S2",
    "UNIT_NAMES",
    "GroundMotion",
    "GroundMotionPair",
    "PiecewiseEnvelope",
    "RecordFormatError",
    "RotDSpectrum",
    "SaragoniHartEnvelope",
    "ScalingReport",
    "Spectrum",
    "TargetSpectrum",
    "arias_intensity",
    "asce7_design_spectrum",
    "baseline_corrected",
    "bundled_names",
    "clough_penzien",
    "clough_penzien_psd",
    "filtered",
    "isolated_period_range",
    "kanai_tajimi",
    "kanai_tajimi_psd",
    "load_bundled",
    "nigam_jennings_coefficients",
    "parse_units",
    "peak_ground_values",
    "read_pair",
    "read_pair_manifest",
    "read_peer_at2",
    "read_record",
    "read_text_record",
    "resampled",
    "response_spectra",
    "response_spectrum",
    "rotd_spectra",
    "scale_suite",
    "sdof_response",
    "significant_duration",
    "spectrum",
    "suite_spectra",
    "synthetic_pair",
    "velocity_and_displacement",
    "zero_residuals",
]
