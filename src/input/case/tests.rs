//! The case's key ([`Case::key`]): the canonical serialization a restart
//! file's fingerprint is computed from.

use super::Case;
use serde_json::Value;

/// A case that gives every key of the schema (it is parsed, never
/// validated: the key is computed from the parsed case).
const EVERY_KEY: &str = r#"
name = "every key"
description = "a case that gives every key"

[model]
plane = "strain"
thickness = 2.0
integration = "reduced"
symmetric_half = true
twist = false
cyclic = { sectors = 12, faces = ["a1.left", "b.right"] }

[mesh]
refine = 1
refine_region = { x = [0.0, 1.0], y = [0.0, 0.5], levels = 1 }

[[mesh.block]]
body = "a"
name = "a1"
x = [0.0, 1.0]
nx = [2]
rx = [1.5]
y = [0.0, 1.0]
ny = [2]
ry = [0.5]
top = { radius = 10.0, center = 0.5 }
left = { fillet_bottom = 0.35 }
right = { fillet_bottom = 0.45, fillet_top = 0.55 }

[[mesh.block]]
body = "b"
x = [0.0, 1.0]
nx = [3]
y = [-1.0, 0.0]
ny = [4]
bottom = { round_left = 0.1, round_right = 0.2, chamfer_left = [0.3, 0.31], chamfer_right = 0.4, fillet_left = 0.6, fillet_right = 0.7 }

[[mesh.interface]]
name = "c"
upper = "a1"
lower = "b"
matching = false

[materials.a]
young = 1000.0
poisson = 0.3
yield_stress = 10.0
hardening = 5.0

[materials.b]
young = 2000.0
poisson = 0.25

[interface.c]
law = "power"
c_n = 0.001
m = 0.5
weights = "lumped"
gap = 0.01
start_pressure = 5.0
gap_history = "ramp"

[interface.c.tangential]
r = 1.0
s = 0.5
kp_ratio = 0.5
mu = 0.3
beta = 0.8
n = 2.0
yield_ratio = 0.6
scheme = "return-mapping"
memory = "kinematic"
backbone = "bilinear"

[[boundary]]
set = "b.bottom"
ux = 0.0
uy = 0.0
x_range = [0.0, 1.0]
y_range = [-1.0, -1.0]
history = "ramp"
rotation = 0.001

[[load]]
edges = "a1.top"
pressure = 10.0
shear = 1.0
x_range = [0.0, 0.5]
y_range = [1.0, 1.0]
history = [[0.0, 0.0], [1.0, 1.0]]
hoop_shear = 2.0
torque = 3.0

[[force]]
nodes = "a1.left"
fx = 1.0
fy = -1.0
x_range = [0.0, 0.0]
y_range = [0.0, 1.0]
history = "ramp"

[history]
ramp = [[0.0, 0.0], [1.0, 1.0], [2.0, 0.5]]

[[pretension]]
name = "bolt"
body = "a"
y = 0.5
force = 100.0
history = "ramp"
lock = true

[[probe]]
name = "p"
at = [0.5, 0.5]
body = "a"

[[probe]]
name = "q"
nodes = "a1.top"
statistic = "max"

[solver]
method = "modified-newton"
step_control = "fixed"
max_increment = 0.2
plastic_strain_step = 0.001
increments = 10
first_increment = 0.05
max_iterations = 50
residual_tolerance = 1e-9
displacement_tolerance = 1e-7
max_cutbacks = 5
acceleration = "none"
anderson_depth = 3
locate_first_yield = false
line_search = false
interface_loop = false
stabilization = "off"
stabilization_energy = 0.01

[output]
probe = [0.25, 0.0]
vtu = true
vtu_every = 2
vtu_format = "ascii"
event_tolerance = 1e-4

[adapt]
tolerance = 0.01
quantity = "total_load"
over = "history"
max_cycles = 3
max_dofs = 1000
fraction = 0.4
"#;

fn key(text: &str) -> String {
    Case::parse(text, "case.toml")
        .unwrap_or_else(|e| panic!("{e}"))
        .key()
}

/// `text` with `old` (which it holds exactly once) replaced by `new`.
fn edited(text: &str, old: &str, new: &str) -> String {
    assert_eq!(text.matches(old).count(), 1, "{old:?} once in the case");
    text.replacen(old, new, 1)
}

/// The same case written otherwise: tables and keys in another order,
/// other whitespace, comments, inline tables for sub-tables, another
/// description, no description at all: the same key. Numbers written
/// otherwise (`1e3` for `1000.0`) are the same numbers.
#[test]
fn the_key_is_the_cases_content_not_its_text() {
    let a = r#"
# a two-block column
name = "column"
description = "the first text"

[model]
plane = "stress"   # per mm
thickness = 1.0

[[mesh.block]]
body = "top"
x = [0.0, 1.0]
nx = [2]
y = [0.0, 1.0]
ny = [2]

[[mesh.block]]
body = "base"
x = [0.0, 1.0]
nx = [2]
y = [-1.0, 0.0]
ny = [2]

[[mesh.interface]]
name = "joint"
upper = "top"
lower = "base"

[materials.top]
young = 1000.0
poisson = 0.3

[materials.base]
young = 2000.0
poisson = 0.25

[interface.joint]
law = "power"
c_n = 0.001
m = 0.5

[interface.joint.tangential]
r = 1.0
s = 0.5
mu = 0.3

[[boundary]]
set = "base.bottom"
uy = 0.0

[[load]]
edges = "top.top"
pressure = 10.0
"#;
    let b = r#"
[materials]
base = { poisson = 0.25, young = 2e3 }
top = { young = 1e3, poisson = 0.3 }

[[load]]
pressure = 1e1
edges = "top.top"

[model]
thickness = 1
plane = "stress"

[interface.joint]
tangential = { mu = 0.3, s = 0.5, r = 1.0 }
m = 0.5
law = "power"
c_n = 1e-3

[[boundary]]
uy = 0.0
set = "base.bottom"

[mesh]
interface = [{ lower = "base", upper = "top", name = "joint" }]
block = [
  { body = "top", x = [0.0, 1.0], nx = [2], y = [0.0, 1.0], ny = [2] },
  { body = "base", x = [0, 1], nx = [2], y = [-1.0, 0.0], ny = [2] },
]
"#;
    let b = format!("name = \"column\"\ndescription = \"another text\"\n{b}");
    assert_eq!(key(a), key(&b));
    let without = a.replace("description = \"the first text\"\n", "");
    assert_eq!(key(a), key(&without));
    // a number changed anywhere: another key
    assert_ne!(key(a), key(&a.replace("mu = 0.3", "mu = 0.31")));
    assert_ne!(
        key(a),
        key(&a.replace("pressure = 10.0", "pressure = 10.000000000000002"))
    );
    // as the effective case: the values in force, given or not
    assert_eq!(key(a), key(&a.replace("thickness = 1.0\n", "")));
    let ratio = a.replace("mu = 0.3", "mu = 0.3\nyield_ratio = 0.625");
    assert_eq!(key(a), key(&ratio));
    let weights = a.replace("m = 0.5\n", "m = 0.5\nweights = \"lumped\"\ngap = 0.0\n");
    assert_eq!(key(a), key(&weights));
}

/// The key is compact JSON, its objects' keys sorted (it does not depend
/// on the order of the structs' fields), without the case's location,
/// description and command-line record.
#[test]
fn the_key_is_canonical_json() {
    let k = key(EVERY_KEY);
    let v: Value = serde_json::from_str(&k).unwrap();
    assert_eq!(serde_json::to_string(&v).unwrap(), k, "compact, sorted");
    let top: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
    assert_eq!(
        top,
        [
            "adapt",
            "boundary",
            "description",
            "force",
            "history",
            "interface",
            "load",
            "materials",
            "mesh",
            "model",
            "name",
            "output",
            "pretension",
            "probe",
            "rating",
            "solver"
        ]
    );
    let at = |s: &str| k.find(s).unwrap_or_else(|| panic!("{s} in {k}"));
    assert!(at("\"adapt\":") < at("\"boundary\":") && at("\"output\":") < at("\"solver\":"));
    assert_eq!(v["description"], Value::Null);
    assert!(!k.contains("overrides") && !k.contains("source"), "{k}");
}

/// Every key of the schema is part of the key: the key read back as a case
/// is the case (every field, but the location, the description and the
/// command-line record, and the values in force for `thickness` and
/// `yield_ratio`), for the case that gives every key and for each shipped
/// case.
#[test]
fn the_key_holds_every_field_of_the_case() {
    let mut texts = vec![("every key".to_string(), EVERY_KEY.to_string())];
    let cases = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("cases");
    let mut dirs: Vec<_> = std::fs::read_dir(&cases)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    dirs.sort();
    for d in dirs {
        if let Ok(t) = std::fs::read_to_string(d.join("case.toml")) {
            texts.push((d.display().to_string(), t));
        }
    }
    assert!(texts.len() > 10, "{} cases", texts.len());
    // as the key holds them: the effective values
    let effective = |mut c: Case| {
        c.description = None;
        c.model.thickness = super::Thickness(Some(c.model.thickness.value()));
        for law in c.interface.values_mut() {
            if let Some(t) = &mut law.tangential {
                t.yield_ratio = Some(t.yield_ratio());
            }
        }
        format!("{c:?}")
    };
    for (name, text) in texts {
        let case = Case::parse(&text, "case.toml").unwrap();
        let mut v: Value = serde_json::from_str(&case.key()).unwrap();
        // `null` is an absent key in a case file
        fn drop_nulls(v: &mut Value) {
            match v {
                Value::Object(m) => {
                    m.retain(|_, x| !x.is_null());
                    m.values_mut().for_each(drop_nulls);
                }
                Value::Array(a) => a.iter_mut().for_each(drop_nulls),
                _ => {}
            }
        }
        drop_nulls(&mut v);
        let back: Case = serde_json::from_value(v).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(effective(back), effective(case), "{name}");
    }
}

/// A change of any key of the schema changes the key: one edit per key of
/// the case that gives every key, each key its own.
#[test]
fn every_key_of_the_schema_changes_the_key() {
    let edits: &[(&str, &str)] = &[
        ("name = \"every key\"", "name = \"another\""),
        ("plane = \"strain\"", "plane = \"stress\""),
        ("thickness = 2.0", "thickness = 3.0"),
        ("integration = \"reduced\"", "integration = \"full\""),
        ("symmetric_half = true", "symmetric_half = false"),
        ("twist = false", "twist = true"),
        ("sectors = 12", "sectors = 13"),
        (
            "faces = [\"a1.left\", \"b.right\"]",
            "faces = [\"b.right\", \"a1.left\"]",
        ),
        ("refine = 1\n", "refine = 2\n"),
        ("levels = 1 }", "levels = 2 }"),
        ("y = [0.0, 0.5], levels", "y = [0.0, 0.6], levels"),
        ("[mesh]\n", "[mesh]\nfile = \"mesh.msh\"\n"),
        ("name = \"a1\"", "name = \"a2\""),
        ("rx = [1.5]", "rx = [1.6]"),
        ("ry = [0.5]", "ry = [0.6]"),
        ("nx = [3]", "nx = [4]"),
        ("ny = [4]", "ny = [5]"),
        ("x = [0.0, 1.0]\nnx = [2]", "x = [0.0, 1.1]\nnx = [2]"),
        ("y = [-1.0, 0.0]", "y = [-2.0, 0.0]"),
        ("radius = 10.0", "radius = 11.0"),
        ("center = 0.5", "center = 0.6"),
        ("round_left = 0.1", "round_left = 0.15"),
        ("round_right = 0.2", "round_right = 0.25"),
        ("chamfer_left = [0.3, 0.31]", "chamfer_left = [0.3, 0.32]"),
        ("chamfer_left = [0.3, 0.31]", "chamfer_left = [0.29, 0.31]"),
        ("chamfer_right = 0.4", "chamfer_right = 0.41"),
        ("fillet_left = 0.6", "fillet_left = 0.61"),
        ("fillet_right = 0.7", "fillet_right = 0.71"),
        ("fillet_bottom = 0.35", "fillet_bottom = 0.36"),
        ("fillet_bottom = 0.45", "fillet_bottom = 0.46"),
        ("fillet_top = 0.55", "fillet_top = 0.56"),
        ("body = \"b\"\nx", "body = \"a\"\nx"),
        ("name = \"c\"", "name = \"d\""),
        ("upper = \"a1\"", "upper = \"b\""),
        ("lower = \"b\"", "lower = \"a1\""),
        ("matching = false", "matching = true"),
        ("matching = false", "matching = false\nleft = \"a1\""),
        ("matching = false", "matching = false\nright = \"b\""),
        ("matching = false", "matching = false\nupper_curve = \"u\""),
        ("matching = false", "matching = false\nlower_curve = \"l\""),
        (
            "matching = false",
            "matching = false\nupper_surface = \"u\"",
        ),
        (
            "matching = false",
            "matching = false\nlower_surface = \"l\"",
        ),
        ("young = 1000.0", "young = 1001.0"),
        ("poisson = 0.25", "poisson = 0.26"),
        ("yield_stress = 10.0", "yield_stress = 11.0"),
        ("hardening = 5.0", "hardening = 6.0"),
        ("[materials.b]", "[materials.c]"),
        ("law = \"power\"", "law = \"linear\""),
        ("c_n = 0.001", "c_n = 0.002"),
        ("m = 0.5\n", "m = 0.6\n"),
        ("m = 0.5\n", "m = 0.5\na = 1.0\n"),
        ("m = 0.5\n", "m = 0.5\nb = 1.0\n"),
        ("m = 0.5\n", "m = 0.5\nslope = 1.0\n"),
        ("m = 0.5\n", "m = 0.5\np_c = 1.0\n"),
        ("m = 0.5\n", "m = 0.5\ntable = [[0.1, 1.0]]\n"),
        ("weights = \"lumped\"", "weights = \"consistent\""),
        ("gap = 0.01", "gap = 0.02"),
        ("start_pressure = 5.0", "start_pressure = 6.0"),
        ("gap_history = \"ramp\"", "gap_history = \"other\""),
        ("\nr = 1.0\n", "\nr = 1.1\n"),
        ("s = 0.5\n", "s = 0.6\n"),
        ("s = 0.5\n", "s = 0.5\nk_table = [[1.0, 2.0]]\n"),
        ("kp_ratio = 0.5", "kp_ratio = 0.6"),
        ("mu = 0.3", "mu = 0.4"),
        ("beta = 0.8", "beta = 0.9"),
        ("\nn = 2.0", "\nn = 3.0"),
        ("yield_ratio = 0.6", "yield_ratio = 0.7"),
        (
            "scheme = \"return-mapping\"",
            "scheme = \"stiffness-modification\"",
        ),
        ("memory = \"kinematic\"", "memory = \"isotropic\""),
        ("backbone = \"bilinear\"", "backbone = \"iwan\""),
        (
            "backbone = \"bilinear\"",
            "backbone = \"bilinear\"\nchi = 0.5",
        ),
        (
            "backbone = \"bilinear\"",
            "backbone = \"bilinear\"\nspike = 0.5",
        ),
        ("set = \"b.bottom\"", "set = \"b.left\""),
        ("ux = 0.0", "ux = 0.1"),
        ("uy = 0.0", "uy = 0.1"),
        ("x_range = [0.0, 1.0]", "x_range = [0.0, 0.9]"),
        ("y_range = [-1.0, -1.0]", "y_range = [-1.0, -0.9]"),
        ("rotation = 0.001", "rotation = 0.002"),
        (
            "history = \"ramp\"\nrotation",
            "history = \"other\"\nrotation",
        ),
        ("edges = \"a1.top\"", "edges = \"a1.left\""),
        ("pressure = 10.0", "pressure = 11.0"),
        ("shear = 1.0", "shear = 2.0"),
        ("x_range = [0.0, 0.5]", "x_range = [0.0, 0.6]"),
        ("y_range = [1.0, 1.0]", "y_range = [0.9, 1.0]"),
        (
            "history = [[0.0, 0.0], [1.0, 1.0]]",
            "history = [[0.0, 0.0], [1.0, 2.0]]",
        ),
        ("history = [[0.0, 0.0], [1.0, 1.0]]", "history = \"ramp\""),
        ("hoop_shear = 2.0", "hoop_shear = 2.5"),
        ("torque = 3.0", "torque = 3.5"),
        ("nodes = \"a1.left\"", "nodes = \"a1.right\""),
        ("fx = 1.0", "fx = 2.0"),
        ("fy = -1.0", "fy = -2.0"),
        ("x_range = [0.0, 0.0]", "x_range = [0.0, 0.1]"),
        ("y_range = [0.0, 1.0]", "y_range = [0.0, 0.9]"),
        (
            "ramp = [[0.0, 0.0], [1.0, 1.0], [2.0, 0.5]]",
            "ramp = [[0.0, 0.0], [1.0, 1.0], [2.0, 0.6]]",
        ),
        (
            "ramp = [[0.0, 0.0], [1.0, 1.0], [2.0, 0.5]]",
            "ramp = [[0.0, 0.0], [1.0, 1.0], [2.0, 0.5]]\nother = [[0.0, 1.0]]",
        ),
        ("name = \"bolt\"", "name = \"nut\""),
        ("body = \"a\"\ny = 0.5", "body = \"b\"\ny = 0.5"),
        ("y = 0.5\n", "y = 0.25\n"),
        ("y = 0.5\n", "x = 0.5\n"),
        ("y = 0.5\n", "z = 0.5\n"),
        ("force = 100.0", "force = 101.0"),
        ("force = 100.0", "shortening = 0.01"),
        ("lock = true", "lock = false"),
        ("force = 100.0\nhistory = \"ramp\"", "force = 100.0"),
        ("name = \"p\"", "name = \"p2\""),
        ("at = [0.5, 0.5]", "at = [0.5, 0.6]"),
        ("body = \"a\"\n\n[[probe]]", "body = \"b\"\n\n[[probe]]"),
        ("nodes = \"a1.top\"", "nodes = \"b.top\""),
        ("statistic = \"max\"", "statistic = \"min\""),
        ("method = \"modified-newton\"", "method = \"full-newton\""),
        ("step_control = \"fixed\"", "step_control = \"auto\""),
        ("max_increment = 0.2", "max_increment = 0.3"),
        ("plastic_strain_step = 0.001", "plastic_strain_step = 0.002"),
        ("increments = 10", "increments = 11"),
        ("first_increment = 0.05", "first_increment = 0.06"),
        (
            "first_increment = 0.05",
            "first_increment = 0.05\nload_factors = [0.5, 1.0]",
        ),
        ("max_iterations = 50", "max_iterations = 51"),
        ("residual_tolerance = 1e-9", "residual_tolerance = 1e-10"),
        (
            "displacement_tolerance = 1e-7",
            "displacement_tolerance = 1e-8",
        ),
        ("max_cutbacks = 5", "max_cutbacks = 6"),
        ("acceleration = \"none\"", "acceleration = \"anderson\""),
        ("anderson_depth = 3", "anderson_depth = 4"),
        ("locate_first_yield = false", "locate_first_yield = true"),
        ("line_search = false", "line_search = true"),
        ("interface_loop = false", "interface_loop = true"),
        ("stabilization = \"off\"", "stabilization = \"auto\""),
        ("stabilization_energy = 0.01", "stabilization_energy = 0.02"),
        ("probe = [0.25, 0.0]", "probe = [0.25, 0.1]"),
        ("vtu = true", "vtu = false"),
        ("vtu_every = 2", "vtu_every = 3"),
        ("vtu_format = \"ascii\"", "vtu_format = \"binary\""),
        ("event_tolerance = 1e-4", "event_tolerance = 1e-5"),
        ("tolerance = 0.01", "tolerance = 0.02"),
        ("quantity = \"total_load\"", "quantity = \"energy\""),
        ("over = \"history\"", "over = \"end\""),
        ("max_cycles = 3", "max_cycles = 4"),
        ("max_dofs = 1000", "max_dofs = 1001"),
        ("fraction = 0.4", "fraction = 0.5"),
    ];
    let base = key(EVERY_KEY);
    let mut seen = std::collections::BTreeMap::new();
    seen.insert(base.clone(), "the case as given");
    for &(old, new) in edits {
        let k = key(&edited(EVERY_KEY, old, new));
        if let Some(other) = seen.insert(k, new) {
            panic!("{old:?} → {new:?}: the key of {other:?}");
        }
    }
    // tables left out: their keys are gone from the key
    for (table, next) in [
        ("[adapt]", None),
        ("[output]", Some("[adapt]")),
        ("[solver]", Some("[output]")),
        ("[[pretension]]", Some("[[probe]]")),
        ("[[force]]", Some("[history]")),
    ] {
        let start = EVERY_KEY.find(table).unwrap();
        let end = next.map_or(EVERY_KEY.len(), |n| EVERY_KEY.find(n).unwrap());
        let text = format!("{}{}", &EVERY_KEY[..start], &EVERY_KEY[end..]);
        assert_ne!(key(&text), base, "without {table}");
    }
}
