//! Checks of the FFT ocean built from tabulated spectra (`spectrum = "table"`).

use super::*;
use crate::spectrum::{spectrum_csv, DirectionConvention, SpectrumKind};

/// A JONSWAP sea and the table that writes it down, sampled from 0.02 to 2 Hz in 1 % steps and
/// every 2° (nautical, coming from).
fn jonswap_and_its_table(wind_direction_deg: f32) -> (FftOceanParams, InlineSpectrumTable) {
    let p = FftOceanParams { grid: 64, patch_size: 300.0, wind_speed: 12.0, wind_direction_deg, ..Default::default() };
    let n = (100f64.ln() / 1.01f64.ln()).ceil() as i32;
    let freq: Vec<f64> = (0..=n).map(|i| 0.02 * 1.01f64.powi(i)).collect();
    let dir: Vec<f64> = (0..180).map(|j| f64::from(j) * 2.0).collect();
    let g = p.spectrum().unwrap().gridded(freq.clone(), dir.clone());
    let efth = g.efth.chunks_exact(dir.len()).map(<[f64]>::to_vec).collect();
    (p, InlineSpectrumTable { freq_hz: Some(freq), dir_deg: Some(dir), efth, ..Default::default() })
}

fn tabulated(p: &FftOceanParams, t: InlineSpectrumTable) -> FftOceanParams {
    FftOceanParams { spectrum: SpectrumKind::Table, spectrum_table: vec![t], ..p.clone() }
}

/// A fresh directory of this test process (the core's tests do without `tempfile`).
pub(super) fn scratch_dir(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("swell-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn heights(o: &FftOcean) -> Vec<f64> {
    o.cascades[0].fields[cascade::PAIR_H_DX].iter().map(|c| f64::from(c.re)).collect()
}

#[test]
fn a_table_of_swells_own_jonswap_gives_the_same_sea_within_the_interpolation_error() {
    for wind in [0.0, 135.0] {
        let (p, table) = jonswap_and_its_table(wind);
        let a = FftOcean::new(&p).unwrap();
        let b = FftOcean::new(&tabulated(&p, table)).unwrap();
        let (ha, hb) = (heights(&a), heights(&b));
        let rms = |v: &[f64]| (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt();
        let diff: Vec<f64> = ha.iter().zip(&hb).map(|(x, y)| x - y).collect();
        // Same seed, same wave vectors: the same waves, up to interpolating the table.
        assert!(rms(&diff) < 0.02 * rms(&ha), "wind {wind}: rms diff {} of {}", rms(&diff), rms(&ha));
    }
}

#[test]
fn going_to_and_swells_frame_name_the_same_sea_as_coming_from() {
    let (p, table) = jonswap_and_its_table(30.0);
    let base = heights(&FftOcean::new(&tabulated(&p, table.clone())).unwrap());
    for (meaning, shift) in [(DirectionConvention::GoingTo, 180.0), (DirectionConvention::Swell, 90.0)] {
        // Coming from φ is going to φ + 180 and travelling along θ = φ + 90 in swell's frame; the
        // rows are rotated so the directions stay increasing from 0.
        let nd = 180;
        let k = (shift / 2.0) as usize;
        let dir: Vec<f64> = (0..nd).map(|j| f64::from(j as u32) * 2.0).collect();
        let efth = table.efth.iter().map(|row| (0..nd).map(|j| row[(j + nd - k) % nd]).collect()).collect();
        let t = InlineSpectrumTable { dir_deg: Some(dir), efth, ..table.clone() };
        let q = FftOceanParams { spectrum_direction: meaning, ..tabulated(&p, t) };
        let h = heights(&FftOcean::new(&q).unwrap());
        let worst = base.iter().zip(&h).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        assert!(worst < 1e-5, "{meaning}: {worst}");
    }
}

#[test]
fn a_csv_file_relative_to_the_scene_and_an_inline_table_sum() {
    let dir = scratch_dir("csv");
    let (p, table) = jonswap_and_its_table(0.0);
    let grid = FftOcean::new(&tabulated(&p, table.clone())).unwrap().spectrum().stats_grid();
    std::fs::write(dir.join("sea.csv"), spectrum_csv(&grid)).unwrap();
    let mut from_file = FftOceanParams {
        spectrum: SpectrumKind::Table,
        spectrum_file: Some(SpectrumFiles::One("sea.csv".into())),
        ..p.clone()
    };
    from_file.resolve_paths(&dir);
    let a = FftOcean::new(&from_file).unwrap();
    let b = FftOcean::new(&tabulated(&p, table.clone())).unwrap();
    assert_eq!(heights(&a), heights(&b));
    // Two copies summed: twice the variance, the same shape.
    let both = FftOceanParams { spectrum_table: vec![table], ..from_file };
    let c = FftOcean::new(&both).unwrap();
    let ratio = c.sea_state().hs_expected / a.sea_state().hs_expected;
    assert!((ratio - 2f64.sqrt()).abs() < 1e-9, "{ratio}");
}

#[test]
fn table_keys_are_refused_where_they_cannot_apply() {
    let (p, table) = jonswap_and_its_table(0.0);
    let e = |q: FftOceanParams| FftOcean::new(&q).err().unwrap().to_string();
    assert!(e(FftOceanParams { spectrum_table: vec![table.clone()], ..p.clone() })
        .starts_with("water.spectrum_table: a tabulated spectrum needs spectrum = \"table\""));
    assert!(
        e(FftOceanParams { spectrum: SpectrumKind::Table, ..p.clone() }).starts_with("water.spectrum: \"table\" needs")
    );
    let t = tabulated(&p, table.clone());
    assert!(e(FftOceanParams { gamma: 5.0, ..t.clone() }).starts_with("water.gamma: shapes a parametric wind sea"));
    let mut bad = table.clone();
    bad.efth[3][7] = -1.0;
    assert!(e(tabulated(&p, bad)).starts_with("water.spectrum_table[0].efth[3][7] = -1 is outside [0, "));
    let both = InlineSpectrumTable { freq_rad_s: Some(vec![1.0, 2.0, 3.0]), ..table.clone() };
    assert!(e(tabulated(&p, both))
        .starts_with("water.spectrum_table[0].freq_hz: give exactly one of freq_hz and freq_rad_s"));
    let rows = table.efth.len();
    let short = InlineSpectrumTable { efth: table.efth[1..].to_vec(), ..table };
    let text = e(tabulated(&p, short));
    assert!(text.contains(&format!("efth: {} rows for {rows} frequencies", rows - 1)), "{text}");
    let missing = FftOceanParams {
        spectrum: SpectrumKind::Table,
        spectrum_file: Some(SpectrumFiles::One("/nonexistent/buoy.csv".into())),
        ..p
    };
    assert!(e(missing).starts_with("/nonexistent/buoy.csv: "));
}

#[test]
fn the_realised_spectrum_holds_every_wave_once() {
    let (p, table) = jonswap_and_its_table(0.0);
    let o = FftOcean::new(&FftOceanParams { cascades: 3, ..tabulated(&p, table) }).unwrap();
    let grid = o.spectrum().stats_grid();
    let mut held = 0.0;
    for c in &o.cascades {
        c.for_each_wave(|_, _, e| held += e);
    }
    let variance: f64 = o.cascades.iter().map(|c| c.variance).sum();
    // The waves' energies are the random realisation of the variance the cascades expect.
    assert!((held / variance - 1.0).abs() < 0.15, "{held} vs {variance}");
    let realised = o.realised_spectrum(&grid);
    let binned: f64 = realised.oned().iter().zip(realised.df()).map(|(s, df)| s * df).sum();
    // The grid reaches 2 Hz: only the cascades' waves beyond it are left out.
    assert!(binned <= held * (1.0 + 1e-9) && binned > 0.99 * held, "{binned} vs {held}");
}

/// NDBC's published layouts (https://www.ndbc.noaa.gov/measdes.shtml), written here: five bands,
/// every band from 300° with r1 = 0.3 and r2 = 0.15 (no negative lobe to cut), so the mean
/// direction is α1 and the spread sqrt(2 (1 − r1)) exactly. Read through a scene (the key paths
/// the errors name are the scene's), so only with the `render` feature that holds scene/ and world/.
#[cfg(feature = "render")]
#[test]
fn a_buoys_ndbc_files_give_the_expected_hs_and_mean_direction() {
    let freqs = [0.05, 0.075, 0.1, 0.125, 0.15];
    let c11 = [0.5, 3.0, 6.0, 2.0, 0.4];
    let dir = scratch_dir("ndbc");
    let realtime = |name: &str, head: &str, values: &[f64], sep: bool| {
        let cells: Vec<String> = values.iter().zip(freqs).map(|(v, f)| format!("{v:.3} ({f:.3})")).collect();
        let text = format!(
            "#YY  MM DD hh mm {}{head}_1 (freq_1) {head}_2 (freq_2) ... >\n2020 06 08 03 50 {}{}\n2020 06 08 03 20 {}{}\n",
            if sep { "Sep_Freq  < " } else { "" },
            if sep { "0.225 " } else { "" },
            cells.join(" "),
            if sep { "0.225 " } else { "" },
            cells.iter().map(|_| "999.0 (0.1)").collect::<Vec<_>>().join(" "),
        );
        std::fs::write(dir.join(name), text).unwrap();
    };
    realtime("b.data_spec", "spec", &c11, true);
    realtime("b.swdir", "alpha1", &[300.0; 5], false);
    realtime("b.swdir2", "alpha2", &[300.0; 5], false);
    realtime("b.swr1", "r1", &[0.3; 5], false);
    realtime("b.swr2", "r2", &[0.15; 5], false);
    let historical = |name: &str, values: &[f64]| {
        let header: Vec<String> = freqs.iter().map(|f| format!("{f:.4}")).collect();
        let row: Vec<String> = values.iter().map(|v| format!("{v}")).collect();
        let text =
            format!("#YY  MM DD hh mm {}\n#yr  mo dy hr mn\n2019 02 06 00 40 {}\n", header.join(" "), row.join(" "));
        std::fs::write(dir.join(name), text).unwrap();
    };
    historical("bw2019.txt", &c11);
    historical("bd2019.txt", &[300.0; 5]);
    historical("bi2019.txt", &[300.0; 5]);
    // r1 and r2 in hundredths, as NDBC archives them.
    historical("bj2019.txt", &[30.0; 5]);
    historical("bk2019.txt", &[15.0; 5]);
    let m0: f64 = {
        let g = crate::spectrum::GriddedSpectrum { freq_hz: freqs.to_vec(), dir_deg: vec![0.0], efth: c11.to_vec() };
        g.variance()
    };
    for files in [
        ["b.data_spec", "b.swdir", "b.swdir2", "b.swr1", "b.swr2"],
        ["bw2019.txt", "bd2019.txt", "bi2019.txt", "bj2019.txt", "bk2019.txt"],
    ] {
        let text = format!(
            "[water]\nmodel = 'fft'\nspectrum = 'table'\ngrid = 64\npatch_size = 2000.0\n[water.ndbc]\ndensity = '{}'\nalpha1 = '{}'\nalpha2 = '{}'\nr1 = '{}'\nr2 = '{}'\n",
            files[0], files[1], files[2], files[3], files[4]
        );
        let mut scene = crate::scene::Scene::from_toml(&text, "buoy.toml").unwrap();
        scene.resolve_paths(&dir);
        let stats = crate::world::sea_stats(&scene, 0.0).unwrap();
        // C11 carried whole into E(f, θ): the same Hs as the density alone (dd x 1 row = 1).
        assert!((stats.hs_expected_m - 4.0 * m0.sqrt()).abs() < 1e-9, "{files:?}: {stats:?}");
        assert!((stats.dpm_expected_deg.unwrap() - 300.0).abs() < 1e-9, "{stats:?}");
        let spread = (2.0 * (1.0 - 0.3f64)).sqrt().to_degrees();
        assert!((stats.dspr_expected_deg.unwrap() - spread).abs() < 1e-6, "{stats:?}");
        assert!((stats.tp_expected_s.unwrap() - 10.0).abs() < 1.0, "{stats:?}");
    }
    // A file cut short, a bad time, r1 out of range: named.
    let e = |ndbc: &str| {
        let text = format!("[water]\nmodel = 'fft'\nspectrum = 'table'\n[water.ndbc]\n{ndbc}");
        let mut scene = crate::scene::Scene::from_toml(&text, "t").map_err(|e| e.to_string())?;
        scene.resolve_paths(&dir);
        crate::world::sea_stats(&scene, 0.0).map(|_| ()).map_err(|e| e.to_string())
    };
    let files = "density = 'b.data_spec'\nalpha1 = 'b.swdir'\nalpha2 = 'b.swdir2'\nr1 = 'b.swr1'\nr2 = 'b.swr2'\n";
    let msg = e(&format!("{files}time = '2021-01-01 00:00'\n")).unwrap_err();
    assert!(msg.contains("water.ndbc.time: no record at 2021-01-01 00:00 in "), "{msg}");
    let msg = e(&format!("{files}time = 'noon'\n")).unwrap_err();
    assert!(msg.contains("water.ndbc.time: `noon` is not a time"), "{msg}");
    std::fs::write(dir.join("cut.txt"), "#YY  MM DD hh mm .0500 .0750\n2019 02 06 00 40 1.0\n").unwrap();
    let msg = e(&files.replace("b.data_spec", "cut.txt")).unwrap_err();
    assert!(msg.contains("cut.txt: line 2: 1 values for the header's 2 frequencies (cut short?)"), "{msg}");
    historical("bad_r1.txt", &[130.0; 5]);
    let msg = e(&files
        .replace("b.data_spec", "bw2019.txt")
        .replace("b.swdir'", "bd2019.txt'")
        .replace("b.swdir2", "bi2019.txt")
        .replace("b.swr1", "bad_r1.txt")
        .replace("b.swr2", "bk2019.txt"))
    .unwrap_err();
    assert!(msg.contains("bad_r1.txt: r1[0] at 0.05 Hz = 1.3 is outside [0, 1] (or 999, missing)"), "{msg}");
    let msg = e(&format!("{files}dir_step_deg = 7.0\n")).unwrap_err();
    assert!(msg.contains("water.ndbc.dir_step_deg = 7 is outside [1, 45] degrees, dividing 360"), "{msg}");
}
