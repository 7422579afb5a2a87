//! The load-approach curve of a Greenwood-Williamson surface and its best
//! power law u_N = c_N p^m (Buczkowski & Kleiber 1992, eq. 2.1).

use super::gw::Gw;

/// One point of the curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// Approach u_N = d₀ − d, mm.
    pub approach: f64,
    /// Nominal pressure, MPa.
    pub pressure: f64,
}

/// The least-squares power law over a pressure range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PowerFit {
    /// c_N, mm/MPa^m.
    pub c_n: f64,
    pub m: f64,
    /// max |c_N p^m − u| / u over the fitted points.
    pub max_error: f64,
    /// root mean square of the same.
    pub(crate) rms_error: f64,
}

/// `n` pressures spaced evenly in log p from `a` to `b` (both included).
pub fn log_space(a: f64, b: f64, n: usize) -> Vec<f64> {
    let (la, lb) = (a.ln(), b.ln());
    (0..n)
        .map(|k| {
            if k == 0 {
                a
            } else if k + 1 == n {
                b
            } else {
                (la + (lb - la) * k as f64 / (n - 1) as f64).exp()
            }
        })
        .collect()
}

/// The curve at the given pressures, approaches measured from the
/// separation `d0`: u = d₀ − d(p).
pub fn curve(gw: &Gw, d0: f64, pressures: &[f64]) -> Vec<Point> {
    pressures
        .iter()
        .map(|&p| Point {
            approach: d0 - gw.separation(p),
            pressure: p,
        })
        .collect()
}

/// Least squares of ln u = ln c_N + m ln p over `points` (all with u > 0 and
/// p > 0), with the fit's relative error in u. None with fewer than two
/// points or no spread in p.
pub fn power_law(points: &[Point]) -> Option<PowerFit> {
    let n = points.len() as f64;
    if points.len() < 2 {
        return None;
    }
    let xs: Vec<f64> = points.iter().map(|q| q.pressure.ln()).collect();
    let ys: Vec<f64> = points.iter().map(|q| q.approach.ln()).collect();
    let mx = xs.iter().sum::<f64>() / n;
    let my = ys.iter().sum::<f64>() / n;
    let sxx: f64 = xs.iter().map(|x| (x - mx).powi(2)).sum();
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    if sxx.is_nan() || sxx <= 0.0 || ys.iter().any(|y| !y.is_finite()) {
        return None;
    }
    let m = sxy / sxx;
    let c_n = (my - m * mx).exp();
    let errs: Vec<f64> = points
        .iter()
        .map(|q| (c_n * q.pressure.powf(m) - q.approach).abs() / q.approach)
        .collect();
    Some(PowerFit {
        c_n,
        m,
        max_error: errs.iter().copied().fold(0.0, f64::max),
        rms_error: (errs.iter().map(|e| e * e).sum::<f64>() / n).sqrt(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_space_ends_exactly() {
        let v = log_space(10.0, 200.0, 7);
        assert_eq!((v[0], v[6]), (10.0, 200.0));
        assert!(v.windows(2).all(|w| w[1] > w[0]));
        assert!((v[3] - (2000f64).sqrt()).abs() < 1e-12);
    }

    #[test]
    fn too_few_points_give_no_fit() {
        let p = Point {
            approach: 1.0,
            pressure: 1.0,
        };
        assert!(power_law(&[p]).is_none());
        assert!(power_law(&[p, p]).is_none());
    }
}
