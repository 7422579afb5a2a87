use super::*;

const MATERIALS: &str = "[materials]\na = { young = 206000.0, poisson = 0.3 }\nb = { young = 206000.0, poisson = 0.3 }\n";

fn gw_input(surface: &str, fit: &str) -> Input {
    let text = format!("{MATERIALS}[surface]\nmodel = \"gw\"\n{surface}[fit]\n{fit}");
    parse(&text, "s.toml").unwrap()
}

fn refusal(input: &Input) -> String {
    prepare(input, "s.toml", Path::new("."))
        .unwrap_err()
        .to_string()
}

/// The no-contact fit range is refused by `prepare`, which maps the
/// pressures to separations with three bisections and never builds the
/// curve or the fit (those are in `calibrate`, after it). The same input
/// with the roughness in its usual range prepares.
#[test]
fn a_fit_range_where_no_summit_touches_is_refused_before_the_fit() {
    // σ in µm written as mm: the key at fault is surface.sigma
    let input = gw_input(
        "density = 2e3\nradius = 0.05\nsigma = 1.0\n",
        "pressure = [1e-3, 1e-2]\n",
    );
    let e = refusal(&input);
    assert!(
        e.starts_with("s.toml: surface.sigma: 1 mm is above the usual range")
            && e.contains("no summit touches at the lower fit pressure fit.pressure = 1e-3 MPa")
            && e.contains(
                "surface.density = 2e3 /mm², surface.radius = 0.05 mm, surface.sigma = 1 mm"
            ),
        "{e}"
    );
    // a negative ν (warned) is not blamed for it
    let text = "[materials]\na = { young = 1.2e6, poisson = -0.2 }\nb = { young = 1.2e6, poisson = 0.1 }\n\
                [surface]\nmodel = \"gw\"\ndensity = 1e6\nradius = 10.0\nsigma = 0.1\n[fit]\npressure = [1e-3, 1e-2]\n";
    let e = refusal(&parse(text, "s.toml").unwrap());
    assert!(
        e.starts_with("s.toml: fit.pressure: no summit touches"),
        "{e}"
    );
    // every value usual, the pressures too low for this stiff, coarse surface
    let text = "[materials]\na = { young = 1.2e6, poisson = 0.1 }\nb = { young = 1.2e6, poisson = 0.1 }\n\
                [surface]\nmodel = \"gw\"\ndensity = 1e6\nradius = 10.0\nsigma = 0.1\n[fit]\npressure = [1e-3, 1e-2]\n";
    let e = refusal(&parse(text, "s.toml").unwrap());
    assert!(
        e.starts_with("s.toml: fit.pressure: no summit touches")
            && e.contains("surface.sigma = 0.1 mm"),
        "{e}"
    );
    // the example's surface at the same pressures: summits touch
    let input = gw_input(
        "density = 2e3\nradius = 0.05\nsigma = 1e-3\n",
        "pressure = [1e-3, 1e-2]\n",
    );
    let p = prepare(&input, "s.toml", Path::new(".")).unwrap();
    assert!(p.contacts_lo > NO_CONTACT && p.d0 > p.d_lo && p.d_lo > p.d_hi);
}

#[test]
fn unit_slips_warn_and_calibrate() {
    let input = gw_input(
        "density = 1e12\nradius = 0.05\nsigma = 1.0\n",
        "pressure = [10.0, 200.0]\n",
    );
    let cal = calibrate(&input, "s.toml", Path::new(".")).unwrap();
    let keys: Vec<&str> = cal.warnings.iter().map(|w| w.key.as_str()).collect();
    // the density does not bring summits into contact: at a given pressure
    // their number per mm² goes with p / (E* β^½ σ^{3/2}), and σ is 1000× off
    assert_eq!(
        keys,
        ["surface.density", "surface.sigma", "fit.pressure"],
        "{:?}",
        cal.warnings
    );
    assert!(cal.warnings[2].message.contains("summits per mm² touch"));
    let json = cal.fit_json("s.toml");
    assert_eq!(json["warnings"].as_array().unwrap().len(), 3);
    let toml = cal.interface_toml("s.toml");
    assert!(
        toml.contains("# WARNING: s.toml: surface.sigma: 1 mm is above"),
        "{toml}"
    );
}

#[test]
fn subnormal_and_huge_values_name_their_key() {
    for (surface, fit, key) in [
        (
            "density = 2e3\nradius = 0.05\nsigma = 1e-310\n",
            "pressure = [10.0, 200.0]\n",
            "surface.sigma: 1e-310 is a subnormal",
        ),
        (
            "density = 1e300\nradius = 0.05\nsigma = 1e-3\n",
            "pressure = [10.0, 200.0]\n",
            "surface.density: 1e300 /mm² is far outside",
        ),
        (
            "density = 2e3\nradius = 0.05\nsigma = 1e-3\n",
            "pressure = [1e-320, 200.0]\n",
            "fit.pressure: 1e-320 is a subnormal",
        ),
        (
            "density = 2e3\nradius = 0.05\nsigma = 1e-3\n",
            "pressure = [10.0, 200.0]\nreference_pressure = 1e-15\n",
            "fit.reference_pressure: 1e-15 MPa is far outside",
        ),
    ] {
        let e = refusal(&gw_input(surface, fit));
        assert!(e.starts_with(&format!("s.toml: {key}")), "{key}: {e}");
    }
}
