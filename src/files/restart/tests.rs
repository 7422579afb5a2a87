//! Unit tests of the restart format and its checks.

use super::*;

/// The streamed checksum equals the one-shot checksum for any split of
/// the bytes, word-aligned or not.
#[test]
fn the_streamed_checksum_does_not_depend_on_the_split() {
    let bytes: Vec<u8> = (0..1000u32).map(|i| (i * 37 % 251) as u8).collect();
    let whole = fnv1a(&bytes);
    for step in [1, 3, 7, 8, 9, 64, 999] {
        let mut f = Fnv::default();
        for piece in bytes.chunks(step) {
            f.update(piece);
        }
        assert_eq!(f.finish(), whole, "pieces of {step}");
    }
    // and a change anywhere changes it
    let mut other = bytes.clone();
    other[997] ^= 1;
    assert_ne!(fnv1a(&other), whole);
}

fn model() -> Model {
    Model::parse(
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/cases/punch-plane-stress/case.toml"
        )),
        "case.toml",
    )
    .unwrap()
}

/// A checkpoint after `n` increments of the case's schedule, as a run
/// leaves it (no solve: the state stays the initial one), with a VTU
/// file per increment; each increment's records those of the state at its
/// load factor ([`honest`]), the reactions of its record made up.
fn checkpoint(model: &Model, n: usize) -> (Checkpoint, Vec<(f64, String)>) {
    let mut ck = Checkpoint::initial(model);
    let mut pvd = Vec::new();
    for k in 1..=n {
        let t = ck.stepper.next(ck.lambda).unwrap();
        ck.stepper.accepted(ck.lambda, t, 3, 0.0);
        ck.last_step = t - ck.lambda;
        ck.lambda = t;
        ck.increments.push(Increment {
            increment: k,
            load_factor: t,
            iterations: 3,
            cutbacks: 0,
            measures: Measures::default(),
            joints: Vec::new(),
            sections: Vec::new(),
            record: (0..model.plan.width()).map(|i| (k * i) as f64).collect(),
            von_mises_away: f64::NAN,
        });
        honest(model, &mut ck);
        pvd.push((t, vtu_name(k)));
    }
    (ck, pvd)
}

/// The last increment's records made the committed state's (at the
/// checkpoint's load factor), as a run writes them: the curve's measures,
/// the joints' rows and the record from its probes on.
fn honest(model: &Model, ck: &mut Checkpoint) {
    ck.committed.time = ck.lambda;
    let joints = crate::solve::joint_measures(model, &ck.committed, &ck.joint_totals);
    let part = crate::measure::state_part(model, &ck.committed);
    let measures = Measures::of(model, &ck.committed);
    let inc = ck.increments.last_mut().unwrap();
    inc.measures = measures;
    inc.joints = joints;
    let start = model.plan.layout.probes.start;
    inc.record.truncate(start);
    inc.record.extend(part);
}

#[test]
fn vtu_names_are_only_the_writers_own() {
    for (k, name) in [
        (1, "vtu/0001.vtu"),
        (12, "vtu/0012.vtu"),
        (12345, "vtu/12345.vtu"),
    ] {
        assert_eq!(vtu_name(k), name);
        assert_eq!(vtu_increment(name), Some(k));
    }
    for bad in [
        "vtu/001.vtu",
        "vtu/00001.vtu",
        "vtu/+001.vtu",
        "vtu/0001.vtu/",
        "vtu//0001.vtu",
        "vtu/../0001.vtu",
        "/vtu/0001.vtu",
        "./vtu/0001.vtu",
        "vtu\\0001.vtu",
        "interface/0001.csv",
        "vtu/0001.VTU",
        "vtu/99999999999999999999999.vtu",
        "",
    ] {
        assert_eq!(vtu_increment(bad), None, "{bad}");
    }
}

/// The checks of [`decode`] on checkpoints that encode cleanly (as a
/// forger would write them): each one changed field is refused with
/// its own message, the unchanged one restores exactly.
#[test]
fn decode_refuses_what_the_case_cannot_have_produced() {
    let model = model();
    let (ck, pvd) = checkpoint(&model, 4);
    let (back, series) = decode(&encode(&model, &ck, &pvd), &model).unwrap();
    assert_eq!(series, pvd);
    assert_eq!(back.lambda.to_bits(), ck.lambda.to_bits());
    assert_eq!(back.stepper.pending, ck.stepper.pending);
    assert_eq!(back.increments.len(), 4);
    // the designer's records and events, bit for bit
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    for (a, b) in back.increments.iter().zip(&ck.increments) {
        assert_eq!(bits(&a.record), bits(&b.record));
    }
    let mut c = ck.clone();
    let event = crate::solve::events::Event {
        kind: crate::solve::events::Kind::FullSeparation,
        interface: Some(0),
        load_factor: 0.0875,
        before: 0.075,
        after: 0.0875,
        increment: 2,
        method: crate::solve::events::Method::Bisection,
        converged: true,
        solve_failed: false,
        place: [1.0, 0.0, 1.0, f64::NAN],
        values: [1.0, 2.0, 3.0, 4.0, 5.0],
        record: vec![0.25; model.plan.width()],
    };
    c.events.push(event.clone());
    let (back, _) = decode(&encode(&model, &c, &pvd), &model).unwrap();
    assert_eq!(back.events.len(), 1);
    assert_eq!(back.events[0].pack().len(), event.pack().len());
    for (x, y) in back.events[0].pack().iter().zip(event.pack()) {
        assert_eq!(x.to_bits(), y.to_bits());
    }
    // an event outside its bracket, its increment, or the mesh (issue 27's
    // red team: a forged event was shown as it was)
    let refused_event = |edit: &dyn Fn(&mut crate::solve::events::Event), needle: &str| {
        let mut c = ck.clone();
        let mut e = event.clone();
        edit(&mut e);
        c.events.push(e);
        let err = decode(&encode(&model, &c, &pvd), &model).unwrap_err();
        assert!(err.contains(needle), "{needle}: {err}");
    };
    refused_event(&|e| e.after = 5.0, "outside its bracket");
    refused_event(&|e| e.load_factor = 0.5, "outside its bracket");
    refused_event(&|e| e.place[0] = 1e300, "a place outside any model");
    let refused = |ck: &Checkpoint, pvd: &[(f64, String)], needle: &str| {
        let e = decode(&encode(&model, ck, pvd), &model).unwrap_err();
        assert!(e.contains(needle), "{needle}: {e}");
    };
    // records of another layout than the model's are refused, whatever
    // width the file gives them
    let w = model.plan.width();
    let mut c = ck.clone();
    c.events.push(event.clone());
    for inc in c.increments.iter_mut() {
        inc.record.push(1.0);
    }
    c.events[0].record.push(1.0);
    refused(
        &c,
        &pvd,
        &format!(
            "section records has {} values, the model needs {}",
            4 * (w + 1),
            4 * w
        ),
    );
    c.record_width += 1;
    refused(
        &c,
        &pvd,
        &format!(
            "section record_width: records of {} values, but this case's have {w}",
            w + 1
        ),
    );
    // names: a path outside, an increment not converged, out of order
    for name in ["../x.vtu", "vtu/0005.vtu", "vtu/0001.vtu"] {
        let mut p = pvd.clone();
        p[1].1 = name.into();
        refused(&ck, &p, "is not a name this program writes");
    }
    let mut c = ck.clone();
    c.stepper.pending.remove(0);
    refused(&c, &pvd, "pending schedule");
    let mut c = ck.clone();
    c.stepper.pending.last_mut().unwrap().1 = 1;
    refused(&c, &pvd, "pending schedule");
    let mut c = ck.clone();
    c.last_step = 0.5;
    refused(&c, &pvd, "section last_step");
    let mut c = ck.clone();
    c.cutbacks_total = 3;
    refused(&c, &pvd, "cutbacks in all");
    let mut c = ck.clone();
    c.last_du = vec![0.0; c.committed.u.len()];
    c.last_du[5] = f64::NAN;
    refused(&c, &pvd, "section last_du: value 6 is not finite");
    let mut c = ck.clone();
    c.committed.gauss.update(2, |g| g.peeq = -1e-3);
    refused(&c, &pvd, "Gauss point 3: equivalent plastic strain -1e-3");
    let mut c = ck.clone();
    c.committed.contact[0].mu_f = f64::INFINITY;
    refused(&c, &pvd, "section contact: value 5 is not finite");
    let mut c = ck.clone();
    c.joint_totals[0].work = f64::NAN;
    refused(&c, &pvd, "section joint_totals");
    // every increment has its joint rows: none missing, first or later,
    // and none of NaN
    for missing in [vec![2], vec![0, 1]] {
        let mut c = ck.clone();
        for &k in &missing {
            c.increments[k].joints.clear();
        }
        refused(
            &c,
            &pvd,
            &format!(
                "section joints has {} values, the model needs 44",
                11 * (4 - missing.len())
            ),
        );
    }
    let mut c = ck.clone();
    c.increments[0].joints[0] = JointMeasures::unpack(&[f64::NAN; JointMeasures::PACKED]);
    refused(&c, &pvd, "section joints: value 1 is not finite (NaN)");
    // and its record
    let mut c = ck.clone();
    c.increments[1].record.clear();
    refused(
        &c,
        &pvd,
        &format!(
            "section records has {} values, the model needs {}",
            3 * w,
            4 * w
        ),
    );
    let mut c = ck.clone();
    c.increments[3].measures.max_peeq = f64::NAN;
    refused(&c, &pvd, "section curve: value 39 is not finite");
    let mut c = ck.clone();
    c.increments[1].record[0] = f64::INFINITY;
    refused(&c, &pvd, "section records: value");
    // the last record from its probes on (here the peaks) is the state's
    let mut c = ck.clone();
    let peak = model.plan.layout.bodies.start;
    c.increments[3].record[peak] += 0.5;
    refused(
        &c,
        &pvd,
        &format!(
            "section records: increment 4 (the last): value {} (a body peak) is",
            peak + 1
        ),
    );
    // the last row of the curve is the state's
    let mut c = ck.clone();
    c.increments[3].measures.center_displacement += 0.5;
    refused(
        &c,
        &pvd,
        "section curve: row 4 (the last): centre displacement 0.5",
    );
    // and every row's mean pressure and load are its normal force's
    let mut c = ck.clone();
    c.increments[1].measures.mean_pressure += 100.0;
    refused(&c, &pvd, "section curve: row 2: mean pressure 100 MPa");
    // and the last joints row
    let mut c = ck.clone();
    c.increments[3].joints[0].normal_force = 1.0;
    refused(
        &c,
        &pvd,
        "section joints: increment 4 (the last): interface \"contact\": normal force = 1",
    );
    // an earlier row beyond what the interface carries
    let mut c = ck.clone();
    c.increments[1].joints[0].open = -1.0;
    refused(
        &c,
        &pvd,
        "section joints: increment 2: interface \"contact\": status measures",
    );
    let mut c = ck.clone();
    let mut e = event.clone();
    c.events.push(e.clone());
    c.events.push(e.clone());
    refused(&c, &pvd, "event 2: appears twice");
    c.events.pop();
    c.events[0].interface = Some(7);
    refused(&c, &pvd, "event 1: no such interface");
    e.increment = 9;
    c.events[0] = e;
    refused(&c, &pvd, "event 1: not an increment of the curve");
    let mut c = ck.clone();
    c.elastic_ratio_prev = -1.0;
    refused(&c, &pvd, "section elastic_ratio_prev");
    // forged floats are quoted short
    let mut c = ck.clone();
    c.lambda = 1e300;
    refused(&c, &pvd, "section load_factor: load factor 1e300, but");
    // counters beyond what the case can count
    let most = most_iterations(&model, 4, 0);
    let mut c = ck.clone();
    c.iterations = most as usize;
    c.factorizations = most as usize;
    assert!(decode(&encode(&model, &c, &pvd), &model).is_ok());
    c.factorizations += 1;
    refused(&c, &pvd, "section counters: ");
    // the event searches' share: restored as written, beyond the bound on
    // the run's own iterations, never more than all of them
    let mut c = ck.clone();
    c.iterations = most as usize + 7;
    c.event_iterations = 7;
    let back = decode(&encode(&model, &c, &pvd), &model)
        .expect("the run's own within the bound")
        .0;
    assert_eq!(
        (back.iterations, back.event_iterations),
        (most as usize + 7, 7)
    );
    c.event_iterations = 6;
    refused(&c, &pvd, "section counters: ");
    c.iterations = 3;
    c.event_iterations = 4;
    refused(
        &c,
        &pvd,
        "section event_counters: 4 Newton iterations of event searches",
    );
    // the interface loop's counters: at most a loop per Newton iteration,
    // MAX_INNER iterations per loop, a fallback per loop; restored as written
    let inner = crate::solve::newton::interface_loop::MAX_INNER;
    let mut c = ck.clone();
    c.iterations = 10;
    c.interface.loops = 10;
    c.interface.iterations = 10 * inner;
    c.interface.fallbacks = 10;
    let back = decode(&encode(&model, &c, &pvd), &model)
        .expect("within the bounds")
        .0;
    assert_eq!(
        (
            back.interface.loops,
            back.interface.iterations,
            back.interface.fallbacks
        ),
        (10, 10 * inner, 10)
    );
    for forge in [
        |c: &mut Checkpoint| c.interface.loops = 11,
        |c: &mut Checkpoint| c.interface.iterations += 1,
        |c: &mut Checkpoint| {
            c.interface.loops = 5;
            c.interface.iterations = 5;
        },
    ] {
        let mut f = c.clone();
        forge(&mut f);
        refused(&f, &pvd, "section interface_counters: ");
    }
    // displacements beyond the displacement range
    let mut c = ck.clone();
    c.committed.u[3] = -2e4;
    refused(
        &c,
        &pvd,
        "section u: value 4 is -2e4 mm, beyond the ±1e4 mm",
    );
    let mut c = ck.clone();
    c.last_du = vec![0.0; c.committed.u.len()];
    c.last_du[0] = 1e300;
    refused(&c, &pvd, "section last_du: value 1 is 1e300 mm");
    // a plastic state no return mapping leaves: radial (plane strain
    // numbers) with ε̄ᵖ = √(2/3)|εᵖ| is accepted, a little less is not
    let mut c = ck.clone();
    let ep: [f64; 4] = [2e-3, -1e-3, 5e-4, -1e-3];
    let norm = (ep[0] * ep[0] + ep[1] * ep[1] + ep[3] * ep[3] + 2.0 * ep[2] * ep[2]).sqrt();
    c.committed.gauss.update(5, |g| {
        g.plastic_strain = [ep[0], ep[1], ep[2], ep[3], 0.0, 0.0];
        g.peeq = (2.0f64 / 3.0).sqrt() * norm;
    });
    honest(&model, &mut c);
    assert!(decode(&encode(&model, &c, &pvd), &model).is_ok());
    c.committed.gauss.update(5, |g| g.peeq *= 1.0 - 1e-6);
    refused(
        &c,
        &pvd,
        "Gauss point 6 (body \"punch\"): equivalent plastic strain",
    );
    // a reach the normal law does not give, or below the state's own
    let mut c = ck.clone();
    c.table_reach[0] = Reach { u_n: 1.0, p_n: 1.0 };
    refused(&c, &pvd, "but the normal law gives 1e6 MPa");
    c.table_reach[0] = Reach { u_n: 1.0, p_n: 1e6 };
    assert!(decode(&encode(&model, &c, &pvd), &model).is_ok());
    c.table_reach[0] = Reach {
        u_n: -1e-3,
        p_n: 0.0,
    };
    refused(&c, &pvd, "outside [0, 1e4] mm");
    let fy = FirstYield {
        load_factor: 0.1,
        mean_pressure: 1.0,
        total_load_kn: 1.0,
        x: 0.0,
        depth: 0.0,
        z: 0.0,
        body: model.mesh.bodies[model.mesh.elements[7].body].clone(),
        element: 7,
    };
    let mut c = ck.clone();
    c.first_yield = Some(fy.clone());
    assert!(decode(&encode(&model, &c, &pvd), &model).is_ok());
    c.first_yield = Some(FirstYield {
        element: model.mesh.elements.len(),
        ..fy.clone()
    });
    refused(&c, &pvd, "section first_yield: element");
    c.first_yield = Some(FirstYield {
        body: "elsewhere".into(),
        ..fy.clone()
    });
    refused(&c, &pvd, "section first_yield_body");
    c.first_yield = Some(FirstYield {
        load_factor: 0.9,
        ..fy
    });
    refused(&c, &pvd, "outside the curve's");
    // more bytes than the case can need, refused before anything is decoded
    let mut big = encode(&model, &ck, &pvd);
    big.resize(Bounds::of(&model).restart_bytes as usize + 1, 0);
    let e = decode(&big, &model).unwrap_err();
    assert!(e.contains("bytes, more than the"), "{e}");
}

/// A twisting model's interface states (56 values a point, the vector
/// law's) and its joints' torque rows round-trip, and a forged vector state
/// or torque row is refused.
#[test]
fn a_twisting_models_vector_states_round_trip_and_are_checked() {
    let model = Model::parse(
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/cases/shrink-fit-torque/case.toml"
        )),
        "case.toml",
    )
    .unwrap();
    assert!(model.node_dofs().twist());
    let (mut ck, pvd) = checkpoint(&model, 3);
    // the interference pressed in so far closes the fit at u = 0: a reach above it
    ck.table_reach = vec![crate::model::interface::extrapolation::Reach {
        u_n: 0.01,
        p_n: 100.0,
    }];
    ck.increments[1].joints[0].torque = 1234.5;
    ck.increments[1].joints[0].twist = -2e-4;
    let (back, _) = decode(&encode(&model, &ck, &pvd), &model).unwrap();
    assert_eq!(back.increments[1].joints[0].torque, 1234.5);
    assert_eq!(back.increments[1].joints[0].twist, -2e-4);
    assert_eq!(back.committed.contact, ck.committed.contact);
    let refused = |c: &Checkpoint, needle: &str| {
        let e = decode(&encode(&model, c, &pvd), &model).unwrap_err();
        assert!(e.contains(needle), "{e:?} should contain {needle:?}");
    };
    let mut c = ck.clone();
    c.committed.contact[0].slip2.kappa = -1e-3;
    refused(&c, "interface point 1 (fit): slip length κ");
    let mut c = ck.clone();
    c.committed.contact[2].slip2.mem.e[0] = [1e-3, 0.0];
    refused(
        &c,
        "interface point 3 (fit): a stretch in Jenkins element 1",
    );
    let mut c = ck.clone();
    c.committed.contact[1].u_h = 1e-3;
    refused(&c, "interface point 2 (fit): u_Tθ = 1e-3 mm");
    let mut c = ck.clone();
    c.committed.contact[1].p_h = 5.0;
    refused(&c, "interface point 2 (fit): shear p_Tθ = 5 MPa");
    let mut c = ck.clone();
    c.increments[0].joints[0].torque = f64::NAN;
    refused(&c, "section joints_twist: value 1 is not finite (NaN)");
    // a torque spike beyond what friction holds at the row's normal force
    let mut c = ck.clone();
    let hold = c.increments[1].joints[0].normal_force;
    c.increments[1].joints[0].torque = 1e3 * hold;
    refused(
        &c,
        "section joints_twist: increment 2: interface \"fit\": torque",
    );
    // the last row is the restored state's
    let mut c = ck.clone();
    c.increments[2].joints[0].torque += 1.0;
    refused(
        &c,
        "section joints_twist: increment 3 (the last): interface \"fit\": torque = 1, but the restored state",
    );
}

/// A probe spike in a restart file: a probe value beyond the displacement
/// range in any record, and in the last record anything but the restored
/// state's displacement, are refused (the face coupling's probe on the
/// disk's rim: u_x, u_y, u_θ).
#[test]
fn a_forged_probe_is_refused() {
    let model = Model::parse(
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/cases/face-coupling-torque/case.toml"
        )),
        "case.toml",
    )
    .unwrap();
    let probes = model.plan.layout.probes.clone();
    assert_eq!(probes.len(), 3);
    let (ck, pvd) = checkpoint(&model, 3);
    assert!(decode(&encode(&model, &ck, &pvd), &model).is_ok());
    let refused = |c: &Checkpoint, needle: &str| {
        let e = decode(&encode(&model, c, &pvd), &model).unwrap_err();
        assert!(e.contains(needle), "{e:?} should contain {needle:?}");
    };
    let mut c = ck.clone();
    c.increments[1].record[probes.start + 2] = -3e4;
    refused(&c, "section records: increment 2: probe value 3 is -3e4 mm");
    let mut c = ck.clone();
    c.increments[2].record[probes.start + 1] = 0.25;
    refused(
        &c,
        &format!(
            "section records: increment 3 (the last): value {} (a probe) is 0.25, but the restored state (sections u, gauss) gives 0",
            probes.start + 2
        ),
    );
}

/// The sections of a restart file: the name, kind, count and data of each,
/// after the 24 bytes of magic, version, reserved and fingerprint.
fn sections_of(bytes: &[u8]) -> (Vec<u8>, Vec<(String, Vec<u8>)>) {
    let body = &bytes[..bytes.len() - 8];
    let n = u32::from_le_bytes(body[24..28].try_into().unwrap());
    let mut at = 28;
    let mut out = Vec::new();
    for _ in 0..n {
        let len = u16::from_le_bytes(body[at..at + 2].try_into().unwrap()) as usize;
        let name = String::from_utf8(body[at + 2..at + 2 + len].to_vec()).unwrap();
        let kind = body[at + 2 + len];
        let count = u64::from_le_bytes(body[at + 3 + len..at + 11 + len].try_into().unwrap());
        let end = at + 11 + len + count as usize * if kind <= 2 { 8 } else { 1 };
        out.push((name, body[at..end].to_vec()));
        at = end;
    }
    assert_eq!(at, body.len());
    (body[..24].to_vec(), out)
}

/// A restart file of `head` and `sections` (each its whole entry), with
/// its count and checksum.
fn file_of(head: &[u8], sections: &[(String, Vec<u8>)]) -> Vec<u8> {
    let mut out = head.to_vec();
    out.extend_from_slice(&(sections.len() as u32).to_le_bytes());
    for (_, entry) in sections {
        out.extend_from_slice(entry);
    }
    let sum = fnv1a(&out);
    out.extend_from_slice(&sum.to_le_bytes());
    out
}

/// A file of this format holds exactly its sections, in the order of
/// [`SECTIONS`]: each is written (an empty one too: `first_yield` before the
/// first yield, `joints_twist` without twist, `pretension` without
/// sections), each is required (a file without it is refused naming it),
/// and a section of another name is refused; the header's version is this
/// build's, and a file of another version is refused before anything else
/// of it is read, naming both versions.
#[test]
fn a_file_holds_exactly_the_sections_of_its_format() {
    let model = model();
    let (ck, pvd) = checkpoint(&model, 2);
    let bytes = encode(&model, &ck, &pvd);
    assert_eq!(&bytes[8..12], &VERSION.to_le_bytes());
    let (head, sections) = sections_of(&bytes);
    let names: Vec<&str> = sections.iter().map(|s| s.0.as_str()).collect();
    assert_eq!(names, SECTIONS);
    assert!(decode(&file_of(&head, &sections), &model).is_ok());
    for k in 0..sections.len() {
        let mut without = sections.clone();
        let (name, _) = without.remove(k);
        let e = decode(&file_of(&head, &without), &model).unwrap_err();
        assert_eq!(
            e,
            format!("section {name} missing: every restart file of format 5 holds it")
        );
    }
    let mut more = sections.clone();
    let mut extra = 5u16.to_le_bytes().to_vec();
    extra.extend_from_slice(b"extra");
    extra.push(2);
    extra.extend_from_slice(&1u64.to_le_bytes());
    extra.extend_from_slice(&7u64.to_le_bytes());
    more.push(("extra".into(), extra));
    let e = decode(&file_of(&head, &more), &model).unwrap_err();
    assert_eq!(e, "section \"extra\" is no section of restart format 5");
    // a body of a first yield the file does not have
    let mut body = sections.clone();
    let k = names.iter().position(|n| *n == "first_yield_body").unwrap();
    let mut entry = 16u16.to_le_bytes().to_vec();
    entry.extend_from_slice(b"first_yield_body");
    entry.push(4);
    entry.extend_from_slice(&5u64.to_le_bytes());
    entry.extend_from_slice(b"punch");
    body[k].1 = entry;
    let e = decode(&file_of(&head, &body), &model).unwrap_err();
    assert_eq!(
        e,
        "section first_yield_body: \"punch\" without a first yield (section first_yield is empty)"
    );
    // a section of the wrong kind
    let mut kind = sections.clone();
    let at = 2 + "increment".len();
    kind[0].1[at] = 1;
    let e = decode(&file_of(&head, &kind), &model).unwrap_err();
    assert_eq!(e, "section increment: not u64 values");
    // other versions: refused by the header alone (no checksum, no
    // fingerprint, no section read)
    for (version, words) in [
        (2u32, "an earlier asperity (restart format 2)"),
        (0, "an earlier asperity (restart format 0)"),
        (3, "an earlier asperity (restart format 3)"),
        (4, "an earlier asperity (restart format 4)"),
        (6, "a later asperity (restart format 6)"),
    ] {
        let mut other = bytes.clone();
        other[8..12].copy_from_slice(&version.to_le_bytes());
        let e = decode(&other, &model).unwrap_err();
        assert!(
            e.starts_with(&format!(
                "restart.bin was written by {words}; this build reads format 5 only: "
            )),
            "{e}"
        );
        other.truncate(40);
        assert_eq!(decode(&other, &model).unwrap_err(), e);
    }
}
