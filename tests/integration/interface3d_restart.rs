//! A 3D interface across a restart (issue 47): the vector friction states
//! of its face points and the joints' force and moment rows (section
//! `joints_space`) resume a stopped `cases/punch-slab-3d` to the
//! uninterrupted run's files, and forged rows are refused.

use crate::common;
use common::read_out as read;
use common::run_case as run;

/// A forgery: the text its refusal must hold, and the edit of the file.
type Forgery<'a> = (&'a str, &'a dyn Fn(&mut common::Forge));

#[test]
fn a_stopped_3d_joint_resumes_to_the_same_files() {
    let case = common::root().join("cases/punch-slab-3d");
    let dir = common::scratch("interface3d-restart");
    let (whole, part, resumed) = (dir.join("whole"), dir.join("part"), dir.join("resumed"));
    assert_eq!(run(&case, &whole, &[]).0, 0);
    let (code, err) = run(&case, &part, &["--stop-after", "6"]);
    assert_eq!(code, 3, "{err}");
    let mut f = common::Forge::parse(&std::fs::read(part.join("restart.bin")).unwrap());
    // the vector layout; 8 space values a row
    let c = f.f64s("contact");
    assert_eq!(c.len() % 56, 0);
    assert_eq!(f.f64s("joints_space").len(), 8 * 6);
    let r = part.display().to_string();
    let (code, err) = run(&case, &resumed, &["--restart", &r]);
    assert_eq!(code, 0, "{err}");
    for file in [
        "joints.csv",
        "curve.csv",
        "reactions.csv",
        "interface/0010.csv",
    ] {
        assert_eq!(read(&whole, file), read(&resumed, file), "{file}");
    }
}

/// An earlier row's force on A beyond what its normal force and friction
/// can give, and the last row's moment anything but the restored state's
/// own, are refused: exit 2, one line naming restart.bin and the section.
#[test]
fn a_forged_3d_joint_row_is_refused() {
    let case = common::root().join("cases/punch-slab-3d");
    let dir = common::scratch("interface3d-forged");
    let part = dir.join("part");
    let (code, err) = run(&case, &part, &["--stop-after", "4"]);
    assert_eq!(code, 3, "{err}");
    let bin = std::fs::read(part.join("restart.bin")).unwrap();
    let early = |f: &mut common::Forge| {
        let mut t = f.f64s("joints_space");
        t[8 + 2] = 1e9; // increment 2: force along x
        f.set_f64s("joints_space", &t);
    };
    let last = |f: &mut common::Forge| {
        let mut t = f.f64s("joints_space");
        t[8 * 3 + 7] *= 1.0 + 1e-9; // increment 4: the moment about z
        f.set_f64s("joints_space", &t);
    };
    let forgeries: [Forgery; 2] = [
        (
            "section joints_space: increment 2: interface \"contact\": force on A of size",
            &early,
        ),
        (
            "section joints_space: increment 4 (the last): interface \"contact\": moment on A about z = ",
            &last,
        ),
    ];
    for (needle, forge) in forgeries {
        let mut f = common::Forge::parse(&bin);
        forge(&mut f);
        std::fs::write(part.join("restart.bin"), f.bytes()).unwrap();
        let out = dir.join("resumed");
        let r = part.display().to_string();
        let (code, err) = run(&case, &out, &["--restart", &r]);
        assert_eq!(code, 2, "{needle}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(
            err.contains("restart.bin") && err.contains(needle),
            "{needle}: {err}"
        );
        assert!(!out.exists(), "{needle}: output left behind");
    }
}
