//! Measured-sea readers (issue 36): any text read as a spectrum CSV or as an NDBC spectral file
//! either gives a table whose interpolant is finite and non-negative everywhere and whose
//! statistics are finite, or is refused with an error. Never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use swell::spectrum::{parse_ndbc, parse_spectrum_csv, DirectionConvention, Dispersion};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let _ = parse_ndbc(text, "fuzz.data_spec");
    if let Ok(t) = parse_spectrum_csv(text, "fuzz.csv", DirectionConvention::ComingFrom) {
        let s = t.grid().stats();
        assert!(s.hs_m.is_finite() && s.hs_m > 0.0, "{s:?}");
        for v in [s.tp_s, s.dpm_deg, s.dm_deg, s.dspr_deg].into_iter().flatten() {
            assert!(v.is_finite(), "{s:?}");
        }
        for k in [1e-3, 0.05, 0.3, 2.0, 40.0] {
            for theta in [-3.0, 0.0, 0.7, 2.9, 6.0] {
                for d in [Dispersion::Deep, Dispersion::for_depth(Some(3.0))] {
                    let f = t.wavenumber_density(k, theta, &d);
                    assert!(f.is_finite() && f >= 0.0, "{f} at k {k}, θ {theta}");
                }
            }
        }
    }
});
