//! The joint as a designer reads it: per interface and per increment the
//! resultant forces, the mean approach and slip, how much of the interface is
//! open, sticking or slipping, and the frictional energy dissipated so far;
//! per closed load cycle its dissipation and secant stiffness.
//!
//! ```text
//!   horizontal interface                 vertical interface
//!   (A = upper, B = lower)               (A = left, B = right)
//!
//!         body A                           body A │ body B
//!     ───────────────  ← interface                │
//!         body B          walked in +x     n ◄────┤ walked in +y
//!                                                 │ ▲ t
//!     n = +y (from B into A), t = +x       n = −x, t = +y
//! ```
//!
//! Internal convention (the per-pair interface CSVs, `super::PointState`):
//! u_T = (u_B − u_A)·t and p_T is the shear B's springs carry along t, so
//! moving A in +t relative to B gives u_T < 0 and p_T < 0.
//!
//! Joint convention (these outputs): the motion and drag of A relative to B
//! along t, ū_T = −Σ A u_T / Σ A and F_T = −Σ A p_T. Dragging A in +t gives
//! ū_T > 0 and F_T > 0 (a loop that starts in the first quadrant); F_T is the
//! tangential force applied to A that the joint resists. Normal force F_N = Σ
//! A p_N (compressive positive) and mean approach ū_N = Σ A u_N / Σ A have one
//! sign in both conventions.
//!
//! Energies, N·mm, accumulated over committed increments by the trapezoid
//! rule at every integration point (A its area):
//! * dissipation D = Σ A Σ_sliders max(0, ½ (f_n + f_n+1) s), the work of
//!   the law's friction forces f on their own slips s (the point's one
//!   slider under the isotropic memory: ½ (p_T,n + p_T,n+1)(u_p,n+1 −
//!   u_p,n); its Jenkins elements under the kinematic one;
//!   `crate::physics::contact::tangential::Side` and the module `work` there):
//!   it never decreases;
//! * work W = Σ A ½ (p_T,n + p_T,n+1)(u_T,n+1 − u_T,n), the tangential work
//!   done on the interface. With k_T^e constant, W − D is the change of the
//!   energy the sliders' springs store, exact step by step: over a cycle
//!   that returns every spring to its start W = D.
//!
//! Both conventions give the same energies (both factors change sign).
//!
//! With twist (`[model] twist = true`) the slip and shear are 2-vectors,
//! (u_T, u_Tθ) and (p_T, p_Tθ), u_Tθ = u_θB − u_θA = r Δφ around the axis;
//! the energies take their dot products (force and slip vectors of each
//! slider), and three measures more, in the joint convention (A relative to
//! B, about +z by the right hand: θ from r toward the viewer of an r-z plot):
//! the torque T = −Σ A r p_Tθ (N·mm, the torque applied to A that the joint
//! resists), the mean circumferential slip ū_θ = −Σ A u_Tθ / Σ A (mm) and
//! the mean twist φ̄ = −Σ A (u_Tθ / r) / Σ A (rad, A's rotation relative to
//! B). The status of a point comes from |p_T| against its limit.

use crate::model::interface::InterfaceModel;
use crate::physics::contact::tangential::{Side, Side2};
use crate::physics::contact::{PointState, Status, TangentialLaw};
use crate::physics::element::Section;

/// One interface's joint quantities at one increment, in the joint
/// convention (see the module comment). Forces in N for the model as meshed
/// (thickness t, or the full revolution in axisymmetry); measures in mm
/// (plane: length of interface) or mm² (axisymmetric: area).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct JointMeasures {
    /// F_N = Σ A p_N, compressive positive, N.
    pub normal_force: f64,
    /// F_T = −Σ A p_T: the drag of A relative to B along t, N.
    pub tangential_force: f64,
    /// ū_N = Σ A u_N / Σ A (positive = closing), mm.
    pub mean_approach: f64,
    /// ū_T = −Σ A u_T / Σ A: A's motion relative to B along t, mm.
    pub mean_slip: f64,
    /// Measure of the points in each status.
    pub open: f64,
    pub closed: f64,
    pub stick: f64,
    pub micro_slip: f64,
    pub macro_slip: f64,
    /// Frictional energy dissipated so far, N·mm.
    pub dissipation: f64,
    /// Tangential work done on the interface so far, N·mm.
    pub work: f64,
    /// With twist: T = −Σ A r p_Tθ, the torque on A the joint resists, N·mm.
    pub torque: f64,
    /// With twist: ū_θ = −Σ A u_Tθ / Σ A, A's circumferential slip, mm.
    pub hoop_slip: f64,
    /// With twist: φ̄ = −Σ A u_Tθ/r / Σ A, A's twist relative to B, rad.
    pub twist: f64,
    /// In 3D: F_T2 = −Σ A p_T2, the drag of A relative to B along t₂, N.
    pub tangential_force_2: f64,
    /// In 3D: ū_T2 = −Σ A u_T2 / Σ A, A's motion relative to B along t₂, mm.
    pub mean_slip_2: f64,
    /// In 3D: the force the interface exerts on A, Σ A (p_N n + p_T1 t₁ +
    /// p_T2 t₂) in global axes (x, y, z), N; B takes the opposite.
    pub force: [f64; 3],
    /// In 3D: its moment about the interface's moment point
    /// ([`InterfaceModel::moment_point`]), Σ A (x − x₀) × τ, N·mm.
    pub moment: [f64; 3],
}

impl JointMeasures {
    /// Doubles per interface and increment in [`JointMeasures::pack_space`].
    pub(crate) const PACKED_SPACE: usize = 8;

    /// The measures of a 3D interface (restart section `joints_space`):
    /// F_T2, ū_T2, the force and the moment on A.
    pub(crate) fn pack_space(&self) -> [f64; Self::PACKED_SPACE] {
        let (f, m) = (self.force, self.moment);
        [
            self.tangential_force_2,
            self.mean_slip_2,
            f[0],
            f[1],
            f[2],
            m[0],
            m[1],
            m[2],
        ]
    }

    /// The whole part's numbers of a joint measured on one of `sectors`
    /// equal sectors of a cyclic model (the y axis its axis): the normal
    /// force N F_N, the axial force on A N F_y, the moment on A about the
    /// axis N (M_P + P × F)_y (M_P the moment about the moment point P,
    /// so that P × F moves it to the origin, which lies on the axis), the
    /// area in contact N (A_closed + A_stick + A_micro + A_macro) and the
    /// dissipation N D. The forces across the
    /// axis are left out: turned through the N sectors they sum to zero.
    pub fn part(&self, sectors: usize, moment_point: [f64; 3]) -> [f64; 5] {
        let n = sectors as f64;
        let (f, p) = (self.force, moment_point);
        let about_axis = self.moment[1] + (p[2] * f[0] - p[0] * f[2]);
        [
            n * self.normal_force,
            n * f[1],
            n * about_axis,
            n * (self.closed + self.stick + self.micro_slip + self.macro_slip),
            n * self.dissipation,
        ]
    }

    /// Sets the measures of [`JointMeasures::pack_space`] from `v`.
    pub(crate) fn unpack_space(&mut self, v: &[f64]) {
        (self.tangential_force_2, self.mean_slip_2) = (v[0], v[1]);
        self.force = [v[2], v[3], v[4]];
        self.moment = [v[5], v[6], v[7]];
    }

    /// Doubles per interface and increment in [`JointMeasures::pack_twist`].
    pub(crate) const PACKED_TWIST: usize = 3;

    /// The measures of twist (restart section `joints_twist`): T, ū_θ, φ̄.
    pub(crate) fn pack_twist(&self) -> [f64; Self::PACKED_TWIST] {
        [self.torque, self.hoop_slip, self.twist]
    }

    /// Doubles per interface and increment in [`JointMeasures::pack`].
    pub const PACKED: usize = 11;

    /// The layout of the `joints` section of restart files: the fields in
    /// declaration order.
    pub fn pack(&self) -> [f64; Self::PACKED] {
        [
            self.normal_force,
            self.tangential_force,
            self.mean_approach,
            self.mean_slip,
            self.open,
            self.closed,
            self.stick,
            self.micro_slip,
            self.macro_slip,
            self.dissipation,
            self.work,
        ]
    }

    /// The inverse of [`JointMeasures::pack`] (`v` holds at least `PACKED` values).
    pub(crate) fn unpack(v: &[f64]) -> Self {
        JointMeasures {
            normal_force: v[0],
            tangential_force: v[1],
            mean_approach: v[2],
            mean_slip: v[3],
            open: v[4],
            closed: v[5],
            stick: v[6],
            micro_slip: v[7],
            macro_slip: v[8],
            dissipation: v[9],
            work: v[10],
            ..Default::default()
        }
    }
}

/// Running energy totals of one interface (kept in the checkpoint).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct JointTotals {
    /// D so far, N·mm.
    pub dissipation: f64,
    /// W so far, N·mm.
    pub work: f64,
}

/// The dissipation and work of one point of area `area` over one increment
/// from `before` to `after`, each with its normal pressure p_N: D the work
/// of the law's friction forces on their own slips
/// ([`TangentialLaw::slip_work`], never negative; 0 without a law), W the
/// trapezoid of the shear on u_T (see the module comment).
pub(crate) fn point_energy(
    law: Option<&TangentialLaw>,
    area: f64,
    (p0, before): (f64, &PointState),
    (p1, after): (f64, &PointState),
) -> (f64, f64) {
    let d = law.map_or(0.0, |l| l.slip_work(&side(p0, before), &side(p1, after)));
    let p = 0.5 * (before.p_t + after.p_t);
    (area * d, area * p * (after.u_t - before.u_t))
}

/// [`point_energy`] of a point of a twisting model: the vector law's
/// friction work ([`TangentialLaw::slip_work2`]) and the dot product of the
/// mean shear (p_T, p_Tθ) with the change of the slip (u_T, u_Tθ).
pub(crate) fn point_energy_twist(
    law: Option<&TangentialLaw>,
    area: f64,
    (p0, before): (f64, &PointState),
    (p1, after): (f64, &PointState),
) -> (f64, f64) {
    let d = law.map_or(0.0, |l| l.slip_work2(&side2(p0, before), &side2(p1, after)));
    let p = [
        0.5 * (before.p_t + after.p_t),
        0.5 * (before.p_h + after.p_h),
    ];
    (
        area * d,
        area * (p[0] * (after.u_t - before.u_t) + p[1] * (after.u_h - before.u_h)),
    )
}

/// A point's state as the scalar law's side of a step at pressure p_N.
fn side(p_n: f64, s: &PointState) -> Side<'_> {
    Side {
        p_n,
        u_t: s.u_t,
        p_t: s.p_t,
        slip: &s.slip,
    }
}

/// A point's state as the vector law's side of a step at pressure p_N.
fn side2(p_n: f64, s: &PointState) -> Side2<'_> {
    Side2 {
        p_n,
        u_t: [s.u_t, s.u_h],
        p_t: [s.p_t, s.p_h],
        slip: &s.slip2,
    }
}

/// One end of an accepted increment: every dof, the pseudo-time (whose gaps
/// the approach is taken across) and every interface point's state, all
/// interfaces in order.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Snapshot<'a> {
    pub u: &'a [f64],
    pub time: f64,
    pub contact: &'a [PointState],
}

impl<'a> Snapshot<'a> {
    pub fn of(u: &'a [f64], time: f64, contact: &'a [PointState]) -> Self {
        Snapshot { u, time, contact }
    }
}

/// Adds the energies of an accepted increment (committed → trial state) to
/// the running totals, one per interface. Every MPI rank holds every
/// point's tangential state and every dof after the step, so every rank
/// computes the same totals.
pub(crate) fn accumulate(
    interfaces: &[InterfaceModel],
    committed: Snapshot,
    trial: Snapshot,
    totals: &mut [JointTotals],
) {
    let mut q = 0;
    for (im, tot) in interfaces.iter().zip(totals.iter_mut()) {
        let energy = if im.node_dofs.vector_slip() {
            point_energy_twist
        } else {
            point_energy
        };
        let law = im.tangential.as_ref();
        let (g0, g1) = (im.gap_at(committed.time), im.gap_at(trial.time));
        // p_N as the law saw it: across the gap of each end's pseudo-time
        let pressure = |pt, u, gap| im.law.pressure(im.point_kinematics_at(pt, u, gap).0).0;
        for pt in &im.points {
            let (p0, p1) = (pressure(pt, committed.u, g0), pressure(pt, trial.u, g1));
            let (d, w) = energy(
                law,
                pt.area,
                (p0, &committed.contact[q]),
                (p1, &trial.contact[q]),
            );
            tot.dissipation += d;
            tot.work += w;
            q += 1;
        }
    }
}

/// What one integration point contributes to its interface's measures.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PointSample {
    pub area: f64,
    pub p_n: f64,
    pub u_n: f64,
    /// Internal convention: (u_B − u_A)·t and B's shear along t.
    pub u_t: f64,
    pub p_t: f64,
    pub status: Status,
    /// With twist: the radius, u_Tθ and p_Tθ (internal convention); None
    /// without.
    pub hoop: Option<[f64; 3]>,
    /// In 3D: the point's place, frame and second slip and shear.
    pub space: Option<SpaceSample>,
}

/// What a point of a 3D interface adds: where it is (relative to the
/// moment point), its normal and slip frame, u_T2 and p_T2 (internal
/// convention).
#[derive(Clone, Copy, Debug)]
pub(crate) struct SpaceSample {
    pub arm: [f64; 3],
    pub frame: [[f64; 3]; 3],
    pub u_t2: f64,
    pub p_t2: f64,
}

/// Sums point samples into joint measures (joint convention); `per_measure`
/// turns an area into the reported measure (1/thickness for plane models).
pub(crate) fn aggregate(
    samples: impl Iterator<Item = PointSample>,
    per_measure: f64,
    totals: JointTotals,
) -> JointMeasures {
    let mut m = JointMeasures {
        dissipation: totals.dissipation,
        work: totals.work,
        ..JointMeasures::default()
    };
    let mut area = 0.0;
    for s in samples {
        area += s.area;
        m.normal_force += s.area * s.p_n;
        m.tangential_force -= s.area * s.p_t;
        m.mean_approach += s.area * s.u_n;
        m.mean_slip -= s.area * s.u_t;
        if let Some(sp) = s.space {
            m.tangential_force_2 -= s.area * sp.p_t2;
            m.mean_slip_2 -= s.area * sp.u_t2;
            let [n, t1, t2] = sp.frame;
            let tau: [f64; 3] =
                std::array::from_fn(|c| s.area * (s.p_n * n[c] + s.p_t * t1[c] + sp.p_t2 * t2[c]));
            let arm = crate::numbers::vec3::cross(sp.arm, tau);
            for c in 0..3 {
                m.force[c] += tau[c];
                m.moment[c] += arm[c];
            }
        }
        if let Some([r, u_h, p_h]) = s.hoop {
            m.torque -= s.area * r * p_h;
            m.hoop_slip -= s.area * u_h;
            if r > 0.0 {
                m.twist -= s.area * u_h / r;
            }
        }
        let a = s.area * per_measure;
        match s.status {
            Status::Open => m.open += a,
            Status::Closed => m.closed += a,
            Status::Stick => m.stick += a,
            Status::MicroSlip => m.micro_slip += a,
            Status::MacroSlip => m.macro_slip += a,
        }
    }
    if area > 0.0 {
        m.mean_approach /= area;
        m.mean_slip /= area;
        m.mean_slip_2 /= area;
        m.hoop_slip /= area;
        m.twist /= area;
    }
    m
}

/// The joint measures of every interface in a committed state (`u` all
/// dofs at pseudo-time `time`, whose gaps the approach is taken across;
/// `status` and `contact` every point of every interface in order).
pub fn measures(
    interfaces: &[InterfaceModel],
    section: Section,
    time: f64,
    u: &[f64],
    status: &[Status],
    contact: &[PointState],
    totals: &[JointTotals],
) -> Vec<JointMeasures> {
    // plane: areas are length × thickness; axisymmetric: areas of revolution
    let per_measure = if section.axisymmetric {
        1.0
    } else {
        1.0 / section.thickness
    };
    let mut base = 0;
    let mut out = Vec::with_capacity(interfaces.len());
    for (i, im) in interfaces.iter().enumerate() {
        // the gap at the state's pseudo-time (an interference pressed in
        // by its gap_history), as the solver and the interface CSV take it
        let gap = im.gap_at(time);
        let radii = im.twist().then(|| im.point_radii());
        let solid = im.node_dofs.solid();
        let samples = im.points.iter().enumerate().map(move |(j, pt)| {
            let (u_n, u_t) = im.point_kinematics_at(pt, u, gap);
            let space = solid.then(|| SpaceSample {
                arm: crate::numbers::vec3::sub(im.point_position(pt), im.moment_point),
                frame: [pt.normal, pt.tangent, pt.binormal()],
                u_t2: im.point_second_slip(pt, u),
                p_t2: contact[base + j].p_h,
            });
            PointSample {
                area: pt.area,
                p_n: im.law.pressure(u_n).0,
                u_n,
                u_t,
                p_t: contact[base + j].p_t,
                status: status[base + j],
                hoop: radii
                    .as_ref()
                    .map(|r| [r[j], im.point_second_slip(pt, u), contact[base + j].p_h]),
                space,
            }
        });
        let tot = totals.get(i).copied().unwrap_or_default();
        out.push(aggregate(samples, per_measure, tot));
        base += im.points.len();
    }
    out
}

/// A closed load cycle of one interface (see `cycle_windows`).
#[derive(Clone, Debug, PartialEq)]
pub struct Cycle {
    /// Increment numbers (1-based, as in the output) where it starts and ends.
    pub start_increment: usize,
    pub end_increment: usize,
    pub start_time: f64,
    pub end_time: f64,
    /// D at the end minus D at the start, N·mm.
    pub dissipation: f64,
    /// W at the end minus W at the start, N·mm.
    pub work: f64,
    /// ΔF_T / Δū_T between the increments of the cycle's largest and
    /// smallest F_T (of those, equal within `TIP_TIE`, the largest and
    /// the smallest ū_T: the loop's tips when it slides at the extreme
    /// forces), N/mm; None when they have the same ū_T, or when the force
    /// range is round-off ([`held`]: a force held constant has no loop).
    pub secant_stiffness: Option<f64>,
    /// Smallest and largest F_T over the cycle's increments, N.
    pub force_range: [f64; 2],
    /// Smallest and largest ū_T over the cycle's increments, mm.
    pub slip_range: [f64; 2],
    /// ū_T at the loop's tips, mm: at the increment of the smallest F_T and
    /// at that of the largest (the increments the secant stiffness uses).
    pub tip_slip: [f64; 2],
    /// The largest |F_T| or |F_N| over the cycle's increments, N: the scale
    /// against which the force range is round-off ([`held`]; 0: the range's
    /// own magnitude only).
    pub force_scale: f64,
    /// Energies at or below this are the solver's round-off, N·mm: 10⁻¹²
    /// of the run's largest max |F_T| × (ū_T range), or with twist
    /// max |T| × (φ̄ range), over every cycle of every interface ([`cycles`]
    /// sets it; 0 for a cycle alone).
    pub floor: f64,
    /// With twist: the torque-twist loop, as the force-slip one: smallest
    /// and largest T (N·mm) and φ̄ (rad) over the cycle's increments, and
    /// the torsional secant stiffness ΔT/Δφ̄ between the increments of the
    /// largest and smallest T (N·mm/rad; None when they have the same φ̄
    /// or the torque range is round-off, [`held`]),
    /// and φ̄ at those two increments (smallest T first: the loop's tips).
    /// Zero and None without twist.
    pub torque_range: [f64; 2],
    pub twist_range: [f64; 2],
    pub torsional_stiffness: Option<f64>,
    pub tip_twist: [f64; 2],
}

impl Cycle {
    /// The force amplitude F_a = (F_T,hi − F_T,lo) / 2, N (hi, lo: the
    /// loop's tips, the cycle's largest and smallest F_T); 0 when the range
    /// is round-off ([`held`]).
    pub(crate) fn force_amplitude(&self) -> f64 {
        amplitude(self.force_range, self.force_scale)
    }

    /// The slip amplitude u_a = (ū_T,hi − ū_T,lo) / 2 at the loop's tips, mm.
    pub(crate) fn slip_amplitude(&self) -> f64 {
        0.5 * (self.tip_slip[1] - self.tip_slip[0])
    }

    /// The loop's stored energy U = ½ F_a u_a = ΔF_T Δū_T / 8, N·mm: the
    /// largest elastic energy of a linear spring of the secant stiffness
    /// F_a / u_a taken to the amplitude (Ungar & Kerwin 1962, the energy
    /// that the loss factor refers to).
    pub(crate) fn stored_energy(&self) -> f64 {
        let f_a = self.force_amplitude();
        if f_a == 0.0 {
            0.0
        } else {
            0.5 * f_a * self.slip_amplitude()
        }
    }

    /// The loss factor η = D / (2π U) (Ungar & Kerwin 1962, J. Acoust. Soc.
    /// Am. 34, 954: the energy dissipated per cycle over 2π times the energy
    /// stored); None when U ≤ 0 (no loop: no force or no slip range).
    /// Also None when D or U is round-off ([`Cycle::floor`]: an interface
    /// that carries no shear has no loss factor, not a negative one).
    pub fn loss_factor(&self) -> Option<f64> {
        self.ratio(self.stored_energy())
    }

    /// With twist: the torque amplitude T_a = (T_hi − T_lo) / 2, N·mm; 0
    /// when the range is round-off ([`held`]).
    pub(crate) fn torque_amplitude(&self) -> f64 {
        amplitude(self.torque_range, 0.0)
    }

    /// With twist: the twist amplitude φ_a = (φ̄_hi − φ̄_lo) / 2 at the
    /// torque-twist loop's tips, rad.
    pub(crate) fn twist_amplitude(&self) -> f64 {
        0.5 * (self.tip_twist[1] - self.tip_twist[0])
    }

    /// With twist: the torque-twist loop's stored energy U_θ = ½ T_a φ_a =
    /// ΔT Δφ̄ / 8, N·mm (T·φ is work as F·u is: the energy of a torsional
    /// spring of the secant stiffness T_a / φ_a turned to the amplitude,
    /// as [`Cycle::stored_energy`] for the force-slip loop).
    pub(crate) fn torsional_stored_energy(&self) -> f64 {
        let t_a = self.torque_amplitude();
        if t_a == 0.0 {
            0.0
        } else {
            0.5 * t_a * self.twist_amplitude()
        }
    }

    /// With twist: the torsional loss factor η_θ = D / (2π U_θ) (Ungar &
    /// Kerwin 1962, with the torque-twist loop's stored energy
    /// `Cycle::torsional_stored_energy`). D is the whole dissipation of the
    /// cycle, the slip in both directions: for a loop driven by a torque (an
    /// axial force held or absent) it is the torsional loop's. None as
    /// [`Cycle::loss_factor`]: no loop, or round-off energies.
    pub fn torsional_loss_factor(&self) -> Option<f64> {
        self.ratio(self.torsional_stored_energy())
    }

    /// D / (2π u) when u and D are above round-off ([`Cycle::floor`]).
    fn ratio(&self, u: f64) -> Option<f64> {
        (u > self.floor && u > 0.0 && self.dissipation.abs() > self.floor)
            .then(|| self.dissipation / (2.0 * std::f64::consts::PI * u))
    }
}

/// The closed load cycles of a run: pairs (i, j) of indices into `marks`,
/// one entry per committed increment, `Some(history values)` where its
/// pseudo-time is a history breakpoint. A cycle closes at a marked j when
/// its values equal those of the latest marked i before it, at or after the
/// end of the previous cycle, and the values differ at some marked
/// increment in between. Values are equal within 1e-12 of the largest
/// magnitude each history takes at the marked increments.
pub(crate) fn cycle_windows(marks: &[Option<Vec<f64>>]) -> Vec<(usize, usize)> {
    let width = marks.iter().flatten().map(Vec::len).max().unwrap_or(0);
    let mut scale = vec![0.0f64; width];
    for v in marks.iter().flatten() {
        for (s, x) in scale.iter_mut().zip(v) {
            *s = s.max(x.abs());
        }
    }
    let equal = |a: &[f64], b: &[f64]| {
        a.len() == b.len()
            && a.iter()
                .zip(b)
                .zip(&scale)
                .all(|((x, y), s)| (x - y).abs() <= 1e-12 * s)
    };
    let marked: Vec<(usize, &Vec<f64>)> = marks
        .iter()
        .enumerate()
        .filter_map(|(k, v)| v.as_ref().map(|v| (k, v)))
        .collect();
    let mut out = Vec::new();
    let mut from = 0; // index into `marked` of the previous cycle's end
    for jm in 0..marked.len() {
        let (j, vj) = marked[jm];
        let Some(im) = (from..jm).rev().find(|&im| equal(marked[im].1, vj)) else {
            continue;
        };
        if marked[im + 1..jm].iter().any(|(_, v)| !equal(v, vj)) {
            out.push((marked[im].0, j));
            from = jm;
        }
    }
    out
}

/// Forces (torques) within this fraction of the span's largest magnitude
/// of its extreme count as equal when the loop's tips are picked
/// ([`tips`]): equilibrium holds them only to the Newton tolerance (10⁻⁸ of
/// the reference force by default), so an exact comparison would let
/// round-off choose between two increments at the same prescribed extreme
/// (a cycle window from tip to tip, a sliding plateau) whose slips differ.
pub(crate) const TIP_TIE: f64 = 1e-6;

/// Whether a cycle's force (or torque) range [lo, hi] is round-off: within
/// `TIP_TIE` of its largest magnitude or of `scale` (the cycle's
/// [`Cycle::force_scale`]: a force held at zero has a range and a magnitude
/// of noise alike), as the two tips of a loop whose force is held constant
/// (an axial preload under a cycled torque: the extremes differ by 1e-12 of
/// 10 kN). Such a range has no amplitude and no secant stiffness; reporting
/// its difference would be reporting noise. The threshold is the tips' own
/// tie: the solver resolves a joint's force to about 10⁻⁸ of the loads
/// (the Newton tolerance), so an amplitude below 10⁻⁶ of the force is not
/// a measurement this solver can vouch for.
pub fn held(range: [f64; 2], scale: f64) -> bool {
    range[1] - range[0] <= TIP_TIE * range[0].abs().max(range[1].abs()).max(scale)
}

/// (hi − lo) / 2 of a range, 0 where it is [`held`].
fn amplitude(range: [f64; 2], scale: f64) -> f64 {
    if held(range, scale) {
        0.0
    } else {
        0.5 * (range[1] - range[0])
    }
}

/// The measures at the loop's tips over `span`: the increments of the
/// smallest and of the largest force `f` (`key` = (force, slip)), each
/// tie within [`TIP_TIE`] broken by the slip (the smallest at the low tip,
/// the largest at the high one); `scale`: a force magnitude the tie is
/// relative to besides the span's own ([`held`]).
fn tips(
    span: &[(f64, JointMeasures)],
    key: impl Fn(&JointMeasures) -> (f64, f64),
    scale: f64,
) -> Option<(JointMeasures, JointMeasures)> {
    let forces = span.iter().map(|r| key(&r.1).0);
    let scale = forces.clone().fold(scale, |a, f| a.max(f.abs()));
    let f_hi = forces.clone().fold(f64::NEG_INFINITY, f64::max);
    let f_lo = forces.fold(f64::INFINITY, f64::min);
    let tie = TIP_TIE * scale;
    let by_slip =
        |a: &&(f64, JointMeasures), b: &&(f64, JointMeasures)| key(&a.1).1.total_cmp(&key(&b.1).1);
    let hi = span
        .iter()
        .filter(|r| key(&r.1).0 >= f_hi - tie)
        .max_by(by_slip)?;
    let lo = span
        .iter()
        .filter(|r| key(&r.1).0 <= f_lo + tie)
        .min_by(by_slip)?;
    Some((lo.1, hi.1))
}

/// The cycle of one interface over the increments `i..=j` of `rows`
/// (pseudo-time and joint measures per committed increment, in order).
pub(crate) fn cycle_of(rows: &[(f64, JointMeasures)], (i, j): (usize, usize)) -> Cycle {
    let span = &rows[i..=j];
    // F_T is round-off against F_N as well (a shear held at zero)
    let force_scale = span.iter().fold(0.0f64, |a, r| {
        a.max(r.1.tangential_force.abs())
            .max(r.1.normal_force.abs())
    });
    // the loop's tips: the largest and smallest F_T, ties (a plateau of
    // macro-slip, or a window from tip to tip) broken by ū_T
    let (lo, hi) = tips(span, |m| (m.tangential_force, m.mean_slip), force_scale)
        .unwrap_or((rows[j].1, rows[j].1));
    let ds = hi.mean_slip - lo.mean_slip;
    let slip = span.iter().map(|r| r.1.mean_slip);
    // the torque-twist loop's tips, ties (a sliding plateau) broken by φ̄
    let (t_lo, t_hi) = tips(span, |m| (m.torque, m.twist), 0.0).unwrap_or((rows[j].1, rows[j].1));
    let dphi = t_hi.twist - t_lo.twist;
    let twist = span.iter().map(|r| r.1.twist);
    Cycle {
        torque_range: [t_lo.torque, t_hi.torque],
        twist_range: [
            twist.clone().fold(f64::INFINITY, f64::min),
            twist.fold(f64::NEG_INFINITY, f64::max),
        ],
        torsional_stiffness: (dphi != 0.0 && !held([t_lo.torque, t_hi.torque], 0.0))
            .then(|| (t_hi.torque - t_lo.torque) / dphi),
        tip_twist: [t_lo.twist, t_hi.twist],
        start_increment: i + 1,
        end_increment: j + 1,
        start_time: rows[i].0,
        end_time: rows[j].0,
        dissipation: rows[j].1.dissipation - rows[i].1.dissipation,
        work: rows[j].1.work - rows[i].1.work,
        secant_stiffness: (ds != 0.0
            && !held([lo.tangential_force, hi.tangential_force], force_scale))
        .then(|| (hi.tangential_force - lo.tangential_force) / ds),
        force_range: [lo.tangential_force, hi.tangential_force],
        slip_range: [
            slip.clone().fold(f64::INFINITY, f64::min),
            slip.fold(f64::NEG_INFINITY, f64::max),
        ],
        tip_slip: [lo.mean_slip, hi.mean_slip],
        force_scale,
        floor: 0.0,
    }
}

/// Whether pseudo-time `t` is one of the sorted `breakpoints` (within 1e-12
/// of the last one's magnitude: the stepping lands on them exactly or nearly).
pub(crate) fn at_breakpoint(t: f64, breakpoints: &[f64]) -> bool {
    let scale = breakpoints.iter().fold(1.0f64, |a, b| a.max(b.abs()));
    let k = breakpoints.partition_point(|&b| b < t - 1e-12 * scale);
    breakpoints
        .get(k)
        .is_some_and(|&b| (b - t).abs() <= 1e-12 * scale)
}

/// The closed cycles of every interface of a run: `times` and `joints` (one
/// entry per interface) per committed increment, `breakpoints` and
/// `values` the model's histories ([`crate::model::Model::breakpoints`],
/// [`crate::model::Model::history_values`]).
pub fn cycles(
    times: &[f64],
    joints: &[&[JointMeasures]],
    breakpoints: &[f64],
    values: impl Fn(f64) -> Vec<f64>,
    interfaces: usize,
) -> Vec<Vec<Cycle>> {
    let n = joints.len().min(times.len());
    let marks: Vec<Option<Vec<f64>>> = times[..n]
        .iter()
        .map(|&t| at_breakpoint(t, breakpoints).then(|| values(t)))
        .collect();
    let windows = cycle_windows(&marks);
    let mut all: Vec<Vec<Cycle>> = (0..interfaces)
        .map(|k| {
            let rows: Vec<(f64, JointMeasures)> =
                (0..n).map(|r| (times[r], joints[r][k])).collect();
            windows.iter().map(|&w| cycle_of(&rows, w)).collect()
        })
        .collect();
    // the torque-twist loop's energies too (zero without twist)
    let scale = all.iter().flatten().fold(0.0f64, |m, c| {
        let f = c.force_range[0].abs().max(c.force_range[1].abs());
        let t = c.torque_range[0].abs().max(c.torque_range[1].abs());
        m.max(f * (c.slip_range[1] - c.slip_range[0]))
            .max(t * (c.twist_range[1] - c.twist_range[0]))
    });
    for c in all.iter_mut().flatten() {
        c.floor = 1e-12 * scale;
    }
    all
}

#[cfg(test)]
mod tests;
