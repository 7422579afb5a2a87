//! How the report prints a number: four significant digits, plain where a
//! designer reads it plainly, the unit a designer expects (kN, N·m, MPa).

/// Significant digits of every number in the report.
const DIGITS: i32 = 4;

/// `v` to four significant digits: plain from 0.001 to below 10⁶, trailing
/// zeros dropped (`30`, `182.3`, `0.02401`), else in scientific form
/// (`1.234e-5`); `0` for zero, `—` for a number that is not finite.
pub fn figure(v: f64) -> String {
    if !v.is_finite() {
        return "—".to_string();
    }
    if v == 0.0 {
        return "0".to_string();
    }
    let text = format!("{:.*e}", (DIGITS - 1) as usize, v);
    // rounded first, so that 999999.7 (→ 1e6) is written as any larger
    let rounded: f64 = text.parse().unwrap_or(v);
    if (1e-3..1e6).contains(&rounded.abs()) {
        let magnitude = rounded.abs().log10().floor() as i32;
        let decimals = (DIGITS - 1 - magnitude).max(0) as usize;
        return trim_zeros(&format!("{rounded:.decimals$}"));
    }
    match text.split_once('e') {
        Some((mantissa, exponent)) => format!("{}e{exponent}", trim_zeros(mantissa)),
        None => text,
    }
}

/// `12.500` → `12.5`, `30.00` → `30` (a number with a decimal point only).
fn trim_zeros(text: &str) -> String {
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text.to_string()
    }
}

/// `v` and its unit: `30 kN`; `—` alone when `v` is not finite.
pub fn with_unit(v: f64, unit: &str) -> String {
    if !v.is_finite() {
        return "—".to_string();
    }
    if unit.is_empty() {
        figure(v)
    } else {
        format!("{} {unit}", figure(v))
    }
}

/// A force given in N, shown in kN.
pub fn kn(newton: f64) -> String {
    with_unit(newton / 1000.0, "kN")
}

/// A moment given in N·mm, shown in N·m.
pub fn nm(newton_mm: f64) -> String {
    with_unit(newton_mm / 1000.0, "N·m")
}

/// A ratio minus one as a signed percentage: 0.024 → `+2.4 %`.
pub fn percent(ratio: f64) -> String {
    if !ratio.is_finite() {
        return "—".to_string();
    }
    let p = figure(100.0 * ratio);
    if ratio > 0.0 {
        format!("+{p} %")
    } else {
        format!("{p} %")
    }
}

/// The value of a component named as summary.json names them (`fx_n`,
/// `torque_nmm`, `mz_nm`) in the report's unit: N → kN, N·mm and N·m → N·m;
/// with the symbol it stands for (`F_x`, `T`, `M_z`).
pub fn component(name: &str, v: f64) -> (String, String) {
    let symbol = match name.split('_').next().unwrap_or(name) {
        "fx" => "F_x",
        "fy" => "F_y",
        "fz" => "F_z",
        "torque" => "T",
        "mx" => "M_x",
        "my" => "M_y",
        "mz" => "M_z",
        other => other,
    };
    let shown = if name.ends_with("_nmm") {
        nm(v)
    } else if name.ends_with("_nm") {
        with_unit(v, "N·m")
    } else if name.ends_with("_n") {
        kn(v)
    } else {
        figure(v)
    };
    (symbol.to_string(), shown)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn four_significant_digits_plain_or_scientific() {
        let cases = [
            (44.999167860371074, "45"),
            (182.3, "182.3"),
            (178.0, "178"),
            (0.024, "0.024"),
            (-1.186982740e-3, "-0.001187"),
            (31.156348799855657, "31.16"),
            (30000.0, "30000"),
            (123456.7, "123500"),
            (999999.7, "1e6"),
            (1.2884e-16, "1.288e-16"),
            (-2.5e-7, "-2.5e-7"),
            (4.2e9, "4.2e9"),
            (0.0, "0"),
            (-0.0, "0"),
            (-1e-300, "-1e-300"),
            (f64::NAN, "—"),
        ];
        for (v, text) in cases {
            assert_eq!(figure(v), text, "{v}");
        }
        assert_eq!(percent(0.024), "+2.4 %");
        assert_eq!(percent(-0.1), "-10 %");
        assert_eq!(kn(44999.16786), "45 kN");
        assert_eq!(nm(182300.0), "182.3 N·m");
        assert_eq!(component("fy_n", -1500.0), ("F_y".into(), "-1.5 kN".into()));
        assert_eq!(component("mz_nm", 12.0), ("M_z".into(), "12 N·m".into()));
    }
}
