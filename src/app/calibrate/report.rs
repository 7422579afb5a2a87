//! The files `asperity calibrate` writes: `curve.csv`, `fit.json`,
//! `interface.toml` and the figure (docs/calibration.md, "Output files").

use super::fit::{self, Point};
use super::gw::{Asperity, Distribution};
use super::{limits, Calibration};
use crate::physics::contact::Backbone;
use serde_json::json;
use std::fmt::Write as _;

impl Calibration {
    /// `curve.csv`.
    pub(crate) fn curve_csv(&self) -> String {
        let mut s = String::from("approach_mm,pressure_mpa\n");
        for q in &self.curve {
            let _ = writeln!(s, "{:.12e},{:.12e}", q.approach, q.pressure);
        }
        s
    }

    /// `fit.json`.
    pub fn fit_json(&self, source: &str) -> serde_json::Value {
        let g = &self.gw;
        let (model, hardness, k) = match g.asperity {
            Asperity::Elastic => ("elastic (Hertz)", None, None),
            Asperity::Ceb { hardness, k } => (
                "elastic-plastic (Chang, Etsion & Bogy 1987)",
                Some(hardness),
                Some(k),
            ),
        };
        let profile = self.moments.map(|(m, s)| {
            json!({"m0_mm2": m.m0, "m2": m.m2, "m4_per_mm2": m.m4, "bandwidth_alpha": s.alpha})
        });
        json!({
            "input": source,
            "c_n": self.fit.c_n,
            "m": self.fit.m,
            "pressure_range_mpa": self.range,
            "max_relative_error_approach": self.fit.max_error,
            "rms_relative_error_approach": self.fit.rms_error,
            "fit_points": self.fitted.len(),
            "reference_pressure_mpa": self.reference_pressure,
            "d0_mm": self.d0,
            "d0_over_sigma": self.d0 / g.sigma,
            "e_star_mpa": g.e_star,
            "gw": {
                "density_per_mm2": g.density,
                "radius_mm": g.radius,
                "sigma_mm": g.sigma,
                "distribution": match g.distribution {
                    Distribution::Gaussian => "gaussian",
                    Distribution::Exponential => "exponential",
                },
                "asperities": model,
                "hardness_mpa": hardness,
                "ceb_k": k,
                "critical_interference_mm": g.critical_interference().is_finite().then(|| g.critical_interference()),
                "plasticity_index": hardness.map(|h| g.e_star / h * (g.sigma / g.radius).sqrt()),
            },
            "profile": profile,
            "roughness": self.roughness_json(),
            "tangential": self.tangential.as_ref().map(|(t, rows)| json!({
                "mu": t.mu,
                "kp_ratio": t.kp_ratio,
                "memory": t.given.memory,
                "backbone": t.given.backbone,
                "chi": t.given.chi,
                "spike": t.given.spike,
                "g_star_mpa": t.g_star,
                "k_table": rows.iter().map(|&(p, k)| [p, k]).collect::<Vec<_>>(),
            })),
            "warnings": self.warnings.iter().map(|w| w.to_string()).collect::<Vec<_>>(),
        })
    }

    /// `interface.toml`: the two snippets.
    pub(crate) fn interface_toml(&self, source: &str) -> String {
        let [lo, hi] = self.range;
        let f = &self.fit;
        let mut s = String::new();
        let _ = writeln!(s, "# asperity calibrate {source}");
        let _ = writeln!(
            s,
            "# Two interface laws for the same surface; paste one into the case and rename\n# the table to the interface's name ([interface.<name>]). Approaches in mm from\n# the separation where p = {:.4e} MPa; pressures in MPa.\n",
            self.reference_pressure
        );
        for w in &self.warnings {
            let _ = writeln!(s, "# WARNING: {w}");
        }
        for line in self.band_lines() {
            let _ = writeln!(s, "{line}");
        }
        if !self.warnings.is_empty() || self.roughness.is_some() {
            s.push('\n');
        }
        let _ = writeln!(
            s,
            "# power law u_N = c_N p^m fitted over {lo}-{hi} MPa: max relative error in u_N {:.2}%",
            100.0 * f.max_error
        );
        if !(f.m > 0.0 && f.m <= 1.0) {
            let _ = writeln!(
                s,
                "# NOTE: m = {:.4} is outside (0, 1], which the case file refuses: use the table",
                f.m
            );
        }
        let _ = writeln!(
            s,
            "[interface.calibrated_power]\nlaw = \"power\"\nc_n = {:.6e}\nm = {:.6}\n",
            f.c_n, f.m
        );
        let _ = writeln!(
            s,
            "# the curve itself at {} pressures spaced evenly in log p over {lo}-{hi} MPa",
            self.table.len()
        );
        let rows: Vec<String> = self
            .table
            .iter()
            .map(|q| format!("  [{:.9e}, {:.9e}],", q.approach, q.pressure))
            .collect();
        let _ = writeln!(
            s,
            "[interface.calibrated_table]\nlaw = \"table\"\ntable = [\n{}\n]",
            rows.join("\n")
        );
        self.tangential_toml(&mut s);
        s
    }

    /// The roughness model's assumption and its band, as `#` lines.
    fn band_lines(&self) -> Vec<String> {
        let Some(d) = &self.roughness else {
            return Vec::new();
        };
        let mut out = vec![format!(
            "# ASSUMPTION: {} the rms height only; the spectrum is taken self-affine, H = {}{}, between λs and λc (docs/calibration.md, \"From Ra or Rz\")",
            if d.faces.len() > 1 && d.parameter() == "mixed" {
                format!("{} give", d.source())
            } else {
                format!("{} gives", d.source())
            },
            d.hurst,
            if d.hurst_given { " (surface.hurst)" } else { "" }
        )];
        for b in &self.band {
            out.push(match &b.result {
                Ok([c_n, m, eta, beta, sigma, k_lo, k_hi]) => format!(
                    "# at H = {}: c_n = {c_n:.4e}, m = {m:.4} (η = {eta:.3e}/mm², β = {beta:.3e} mm, σ_s = {sigma:.3e} mm){}",
                    b.hurst,
                    if self.tangential.is_some() {
                        format!(", k_T^e = {k_lo:.4e} to {k_hi:.4e} MPa/µm over the range")
                    } else {
                        String::new()
                    }
                ),
                Err(e) => format!("# at H = {}: not calibrated: {e}", b.hurst),
            });
        }
        out
    }

    /// `[interface.calibrated_table.tangential]`: the k_table, kp_ratio (not
    /// with the Iwan backbone) and μ, and memory, backbone, chi and spike when
    /// the input gave them.
    fn tangential_toml(&self, s: &mut String) {
        let Some((t, rows)) = &self.tangential else {
            return;
        };
        let _ = writeln!(
            s,
            "\n# Mindlin-GW elastic shear stiffness k_T^e = η ∫ 8 G* √(β(z−d)) φ(z) dz (MPa/µm) at the\n# table's pressures, G* = {:.1} MPa; elastic summits without micro-slip; paste it\n# under the normal law you chose, as [interface.<name>.tangential]",
            t.g_star
        );
        if matches!(t.backbone, Backbone::Iwan { .. }) {
            let _ = writeln!(
                s,
                "# backbone = \"iwan\": k_T^e is the stiffness at zero shear, falling to 0 at μ p_N;\n# chi is not derived from the surface (default 0: dissipation ∝ amplitude^3)"
            );
        }
        let rows: Vec<String> = rows
            .iter()
            .map(|(p, k)| format!("  [{p:.9e}, {k:.9e}],"))
            .collect();
        let _ = writeln!(
            s,
            "[interface.calibrated_table.tangential]\nk_table = [\n{}\n]",
            rows.join("\n")
        );
        if let Some(kp) = t.kp_ratio {
            let _ = writeln!(
                s,
                "kp_ratio = {}{}",
                limits::exact(kp),
                if kp == 1.0 {
                    "    # elastic up to the friction cap: Mindlin-GW gives no micro-slip branch"
                } else {
                    ""
                }
            );
        }
        let _ = writeln!(s, "mu = {}", limits::exact(t.mu));
        let g = &t.given;
        for (k, v) in [("memory", &g.memory), ("backbone", &g.backbone)] {
            if let Some(v) = v {
                let _ = writeln!(s, "{k} = \"{v}\"");
            }
        }
        for (k, v) in [("chi", g.chi), ("spike", g.spike)] {
            if let Some(v) = v {
                let _ = writeln!(s, "{k} = {}", limits::exact(v));
            }
        }
    }

    /// fit.json's `roughness`: the faces, the assumption and the band.
    fn roughness_json(&self) -> Option<serde_json::Value> {
        let d = self.roughness.as_ref()?;
        let faces: Vec<_> = d
            .faces
            .iter()
            .map(|f| {
                json!({
                    "key": f.key,
                    f.parameter.key(): f.value,
                    "sigma_mm": f.sigma,
                    "cutoff_mm": f.cutoff,
                    "short_cutoff_mm": f.short_cutoff,
                    "rz_over_sigma": f.rz_over_sigma,
                })
            })
            .collect();
        let band: Vec<_> = self
            .band
            .iter()
            .map(|b| match &b.result {
                Ok(v) => json!({"hurst": b.hurst, "c_n": v[0], "m": v[1], "density_per_mm2": v[2],
                    "radius_mm": v[3], "sigma_mm": v[4], "k_t_lo_mpa_per_um": v[5], "k_t_hi_mpa_per_um": v[6]}),
                Err(e) => json!({"hurst": b.hurst, "error": e}),
            })
            .collect();
        let g = &self.gw;
        Some(json!({
            "parameter": d.parameter(),
            "hurst": d.hurst,
            "hurst_given": d.hurst_given,
            "faces": faces,
            "m0_mm2": d.moments.m0,
            "m2": d.moments.m2,
            "m4_per_mm2": d.moments.m4,
            "bandwidth_alpha": d.moments.m0 * d.moments.m4 / (d.moments.m2 * d.moments.m2),
            "eta_beta_sigma": g.density * g.radius * g.sigma,
            "hurst_band": band,
        }))
    }

    /// The summary line's additions: the band of c_N and the k_T^e range.
    pub(super) fn summary_extra(&self) -> String {
        let mut s = String::new();
        let ends: Vec<&[f64; 7]> = self
            .band
            .iter()
            .filter_map(|b| b.result.as_ref().ok())
            .collect();
        if let Some(d) = &self.roughness {
            let _ = write!(s, " (from {}, assumed H = {})", d.source(), d.hurst);
            if ends.len() == 2 {
                let _ = write!(
                    s,
                    "; over H {}-{}: c_n {:.4e} to {:.4e} (m {:.4} to {:.4})",
                    self.band[0].hurst,
                    self.band[1].hurst,
                    ends[0][0],
                    ends[1][0],
                    ends[0][1],
                    ends[1][1]
                );
            }
        }
        if let Some((t, rows)) = &self.tangential {
            let _ = write!(
                s,
                "; k_T^e = {:.4e} to {:.4e} MPa/µm over the range, μ = {}",
                rows[0].1,
                rows[rows.len() - 1].1,
                super::limits::exact(t.mu)
            );
            if ends.len() == 2 && self.roughness.is_some() {
                let _ = write!(
                    s,
                    " (k_T^e at hi over H {}-{}: {:.4e} to {:.4e})",
                    self.band[0].hurst, self.band[1].hurst, ends[0][6], ends[1][6]
                );
            }
        }
        s
    }

    /// The figure: pressure against approach, the GW curve and the power law.
    pub(super) fn chart(&self) -> crate::files::plot::Chart {
        use crate::files::plot::{Chart, Series};
        let [lo, hi] = self.range;
        let f = self.fit;
        let shown: Vec<&Point> = self
            .curve
            .iter()
            .filter(|q| q.pressure >= 0.5 * lo)
            .collect();
        let power = fit::log_space(0.5 * lo, 2.0 * hi, 80)
            .into_iter()
            .map(|p| (1e3 * f.c_n * p.powf(f.m), p))
            .collect();
        Chart {
            title: "Load-approach curve of the rough pair".into(),
            x_label: "approach u_N (µm)".into(),
            y_label: "nominal pressure p (MPa)".into(),
            series: vec![
                Series {
                    label: "Greenwood-Williamson".into(),
                    points: shown
                        .iter()
                        .map(|q| (1e3 * q.approach, q.pressure))
                        .collect(),
                },
                Series {
                    label: format!(
                        "u_N = {:.4e} p^{:.4} (max error {:.2}% over {lo}-{hi} MPa)",
                        f.c_n,
                        f.m,
                        100.0 * f.max_error
                    ),
                    points: power,
                },
            ],
            hlines: vec![(lo, format!("{lo} MPa")), (hi, format!("{hi} MPa"))],
            ..Chart::default()
        }
    }
}
