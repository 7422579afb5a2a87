//! The discrete model built from a case: mesh, element geometry, materials,
//! interfaces, prescribed dofs, external load vector and the sparsity pattern.
//! Everything here is fixed for the whole run; evolving state lives in
//! [`crate::solve::State`].

use crate::error::{Error, Result};
use crate::input::case::{check_case, Case, Integration};
use crate::input::mesh::{Mesh, NodeDofs};
use crate::model::assembly::{Blocks, DofMap, Pattern};
use crate::model::interface::InterfaceModel;
use crate::physics::element::family::{Family, GaussRule};
use crate::physics::element::gauss3::GaussRule3;
use crate::physics::element::solid::ElementGeometry;
use crate::physics::element::solid::ElementVector;
use crate::physics::element::solid3::{ElementGeometry3, Family3};
use crate::physics::material::{Plane, VonMises};

pub mod assembly;
pub mod axis;
pub mod consistency;
use consistency as whole;
pub mod constraint;
pub mod cyclic;
pub mod excluded;
mod hanging;
pub mod history;
pub mod interface;
pub mod loads;
mod measurable;
mod meshes;
pub mod outputs;
pub mod pretension;
pub mod schedule;
pub mod singular;
pub(crate) mod solid_overlap;
pub mod state;
use meshes::{check_mesh, make_mesh};
pub mod supports;
use supports::check_supports;

/// Every body's free thermal strain and material at one pseudo-time, in
/// body order ([`Model::conditions`]).
#[derive(Clone, Debug)]
pub struct Conditions<'m> {
    /// α ΔT h(t): the free thermal strain, or its scale where a field
    /// varies it in space.
    pub thermal: Vec<f64>,
    /// The material of each body at its temperature (where a field varies
    /// it, at the field's factor 1: `Conditions::point_materials` reads
    /// each point's).
    pub materials: Vec<VonMises>,
    /// The temperature field of each body that has one.
    pub fields: Vec<Option<&'m crate::model::loads::thermal::Field>>,
    /// Each body whose material varies from point to point (a field with a
    /// property table): its temperature, its history's factor at this
    /// pseudo-time, and its material as the case gives it.
    varying: Vec<Option<Varying<'m>>>,
}

/// A body whose material follows its temperature field, at one
/// pseudo-time.
#[derive(Clone, Copy, Debug)]
struct Varying<'m> {
    temperature: &'m crate::model::loads::thermal::BodyTemperature,
    factor: f64,
    base: &'m VonMises,
}

impl Conditions<'_> {
    /// The free thermal strain of body `b` at each Gauss point of `geo`.
    pub(crate) fn point_thermal(
        &self,
        b: usize,
        geo: &crate::physics::element::Geometry,
    ) -> [f64; crate::physics::element::family3::MAX_POINTS3] {
        let mut out = [self.thermal[b]; crate::physics::element::family3::MAX_POINTS3];
        if let Some(f) = self.fields[b] {
            for (ip, o) in out.iter_mut().enumerate().take(geo.dv().len()) {
                *o *= f.factor(geo.x(ip));
            }
        }
        out
    }

    /// The material of body `b` at each Gauss point of `geo`: the body's
    /// one where it is uniform; where its field varies it, each point's at
    /// its own temperature T_ref + ΔT h(t) f(x_ip), written into `buf` (one
    /// slot per point, its capacity kept from element to element).
    pub(crate) fn point_materials<'a>(
        &'a self,
        b: usize,
        geo: &crate::physics::element::Geometry,
        buf: &'a mut Vec<VonMises>,
    ) -> crate::physics::material::PointMaterials<'a> {
        use crate::physics::material::PointMaterials;
        let Some(v) = &self.varying[b] else {
            return PointMaterials::Uniform(&self.materials[b]);
        };
        buf.clear();
        buf.extend((0..geo.dv().len()).map(|ip| {
            let f = v.temperature.field_factor(geo.x(ip));
            v.temperature.material(v.base, v.factor * f)
        }));
        PointMaterials::PerPoint(buf)
    }
}

/// The materials of one element's points ([`Model::element_materials`],
/// [`Model::point_materials`]): one for all, or one per point.
#[derive(Clone, Debug)]
pub enum ElementMaterials {
    Uniform(VonMises),
    PerPoint(Vec<VonMises>),
}

impl ElementMaterials {
    /// Point `ip`'s material.
    pub fn at(&self, ip: usize) -> &VonMises {
        match self {
            ElementMaterials::Uniform(m) => m,
            ElementMaterials::PerPoint(m) => &m[ip],
        }
    }
}

/// How a load pattern scales with pseudo-time: by its history's factor
/// (the load factor without one), or by its square (a speed's centrifugal
/// force, ∝ ω²).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Scale {
    Factor(Option<usize>),
    Squared(Option<usize>),
}

/// A mesh an adaptive run refined from the case's ([`crate::app::adapt`]), and
/// how many of its nodes are the start mesh's: a refinement keeps every
/// node and numbers its new ones after them, so nodes `0..start_nodes` are
/// the start mesh's own on every cycle.
pub struct Adapted {
    pub mesh: Mesh,
    pub start_nodes: usize,
    /// The start mesh's discs about its singular points, which
    /// `[adapt] quantity = "max_von_mises"` leaves out on every cycle
    /// ([`excluded`]; None: the quantity is another).
    pub excluded: Option<Vec<excluded::Disc>>,
}

pub struct Model {
    /// The solution settings (method, schedule, tolerances, cutbacks, ...).
    pub solver: crate::input::case::SolverSpec,
    /// What is written, and how often.
    pub output: crate::input::case::OutputSpec,
    /// The designer's outputs: reaction groups, probes, events
    /// ([`crate::model::outputs`]).
    pub plan: crate::model::outputs::Plan,
    /// The case file the model came from (the text's name for [`Model::parse`]).
    pub source: std::path::PathBuf,
    /// What the command line set in place of the case's keys: the run's
    /// advice names the option ([`crate::input::case::overrides`]).
    pub overrides: crate::input::case::overrides::Overrides,
    /// The case's free-text description.
    pub description: Option<String>,
    /// Full or reduced Gauss integration of the elements ([`Model::rule`]
    /// is an element's rule).
    pub integration: Integration,
    /// The effective case (after command-line overrides) without its location
    /// and description, as canonical JSON ([`crate::input::case::Case::key`]):
    /// what a restart file's fingerprint identifies besides the mesh
    /// ([`crate::files::restart::fingerprint`]).
    case_key: String,
    pub name: String,
    pub mesh: Mesh,
    pub plane: Plane,
    pub thickness: f64,
    /// Thickness or revolution: the out-of-plane measure of every integral.
    pub section: crate::physics::element::Section,
    pub symmetric_half: bool,
    /// Each plane family's Gauss rule at the case's integration, in
    /// [`Family::index`] order.
    rules: [GaussRule; 2],
    /// Each solid family's rule (H20, T10), likewise.
    rules3: [GaussRule3; 2],
    /// Element e's Gauss point states are `gauss_offsets[e]..gauss_offsets[e
    /// + 1]` of every state vector ([`Model::points`]).
    gauss_offsets: Vec<usize>,
    /// Material per body.
    pub materials: Vec<VonMises>,
    /// The bodies' uniform temperature changes (`[[temperature]]`; a body
    /// without one keeps its assembly temperature): [`Model::thermal_strains`].
    pub temperatures: Vec<crate::model::loads::thermal::BodyTemperature>,
    /// The speed the bodies spin at (`[speed]`), with its centrifugal
    /// forces: [`Model::external_force`], [`Model::rpm`].
    pub speed: Option<crate::model::loads::speed::Speed>,
    pub interfaces: Vec<InterfaceModel>,
    /// Prescribed dofs and their values at factor 1 (the value at
    /// pseudo-time t: `Model::prescribed_at`).
    pub prescribed: Vec<(usize, f64)>,
    /// The history of each prescribed dof (`None`: the load factor, or the
    /// default ramp); parallel to [`Model::prescribed`].
    pub prescribed_history: Vec<Option<usize>>,
    /// External nodal forces at factor 1 (all dofs) of the loads without a
    /// history of their own: those of the load factor t, or of the default
    /// ramp in a case with histories (the force at pseudo-time t:
    /// [`Model::external_force`]).
    pub f_ext: Vec<f64>,
    /// External nodal forces at factor 1 of the loads with histories, one
    /// vector per history (`Model::patterns`).
    pub loads: Vec<crate::model::loads::LoadPattern>,
    /// Every history of the case: the named ones in name order, then those
    /// given in place (empty: the case has none, and t is the load factor).
    pub histories: Vec<crate::model::history::History>,
    /// Every `[[load]]` and `[[force]]` as a whole (its resultant at factor
    /// 1; [`Model::applied_at`]) and the components of the resultants.
    pub applied: Vec<crate::model::loads::Applied>,
    pub applied_components: crate::model::loads::resultant::Components,
    /// The joints rated to a design standard (`[[rating]]`, [`crate::verdict`]).
    pub ratings: Vec<crate::input::case::rating::RatingSpec>,
    pub dofs: DofMap,
    /// Index of the first interface block in [`Model::blocks`] (elements come first).
    interface_block_base: Vec<usize>,
    /// The lower body's interface node nearest to the output probe.
    pub probe_node: usize,
    /// y of the probe node: depths are measured below it.
    pub surface_y: f64,
    /// Every dof: the mesh's ([`NodeDofs`] per node), then as many per
    /// pretension section (its reference node, [`crate::model::pretension`]).
    n_dofs: usize,
    /// The linear constraints u_s = Σ c u_m + g(t) ([`crate::model::constraint`]).
    pub constraints: crate::model::constraint::Constraints,
    /// A cyclic sector's ties and axis (`[model] cyclic`,
    /// [`crate::model::cyclic`]); None: the mesh is the whole part.
    pub cyclic: Option<crate::model::cyclic::Cyclic>,
    /// The transformation of every block ([`Model::blocks`]) that holds a
    /// slave dof, by block index.
    expansions: std::collections::HashMap<usize, crate::model::constraint::Expansion>,
    /// The pretension sections.
    pub sections: Vec<crate::model::pretension::Section>,
    /// The mesh's singular points: re-entrant corners, the ends of contact
    /// sides at a body's corner, the ends of supports (2D;
    /// [`crate::model::singular`]).
    pub singular: Vec<crate::model::singular::SingularPoint>,
    /// The Gauss points `[adapt] quantity = "max_von_mises"` leaves out
    /// ([`excluded`]); None: the run does not measure that quantity.
    pub excluded: Option<excluded::Excluded>,
    /// The block of each section's reference node (after the interface
    /// points): where a held (locked) shortening gets its diagonal.
    section_block_base: usize,
    /// Force scale for the residual test when nothing is loaded (an open joint
    /// under prescribed displacement): 1e-6 · E_max · model size · thickness, N.
    force_floor: f64,
}

impl Model {
    /// Every dof: the mesh's, then the pretension sections' reference dofs.
    pub fn n_dofs(&self) -> usize {
        self.n_dofs
    }

    /// The number of sectors N of a cyclic sector model (`[model] cyclic`):
    /// the part is N copies of the mesh about the y axis, each loaded alike,
    /// so a force along the axis or a moment about it over the part is N
    /// times the sector's (a force across the axis sums to zero over the
    /// part). None: the mesh is the whole part (or its symmetric half,
    /// [`Model::symmetric_half`]).
    pub fn cyclic_sectors(&self) -> Option<usize> {
        self.cyclic.as_ref().map(|c| c.sectors)
    }

    /// The block of interface `i`'s point `j` in [`Model::blocks`].
    pub(crate) fn interface_block(&self, i: usize, j: usize) -> usize {
        self.interface_block_base[i] + j
    }

    /// The blocks of every interface point, in order: after the elements',
    /// before the sections' (empty without interfaces).
    pub(crate) fn interface_blocks(&self) -> std::ops::Range<usize> {
        let first = self.interface_block_base.first().copied();
        first.unwrap_or(self.section_block_base)..self.section_block_base
    }

    /// The block of pretension section `k`'s reference node.
    pub(crate) fn section_block(&self, k: usize) -> usize {
        self.section_block_base + k
    }

    /// The transformation of block `b` when it holds a slave dof.
    pub(crate) fn expansion(&self, b: usize) -> Option<&crate::model::constraint::Expansion> {
        self.expansions.get(&b)
    }

    /// Force scale of the residual test when nothing is loaded, N.
    pub(crate) fn force_floor(&self) -> f64 {
        self.force_floor
    }

    /// The canonical text of the case that identifies a restart's model.
    pub(crate) fn case_key(&self) -> &str {
        &self.case_key
    }

    /// Parses case text and builds its model, reading and writing no file (the
    /// fuzz target's entry point). `place` names the text in errors.
    pub fn parse(text: &str, place: &str) -> Result<Model> {
        let mut case = Case::parse(text, place)?;
        case.source = place.into();
        Model::build(case)
    }

    /// Validates the case, generates the mesh and builds the model: the case
    /// checked key by key, the mesh made and checked as a whole, then the
    /// materials, the interfaces and the loads and supports, each refused
    /// with the key and place at fault.
    pub fn build(case: Case) -> Result<Model> {
        Model::build_on(case, None)
    }

    /// The case's mesh (blocks or a Gmsh file, `refine_region` applied),
    /// checked, before the model's own changes (a pretension section's cut,
    /// twist's third dof): what an adaptive run refines ([`crate::app::adapt`]).
    pub(crate) fn mesh_of(case: &Case) -> Result<Mesh> {
        let mesh = |case: &Case| {
            check_case(case)?;
            make_mesh(case, &case.source.display().to_string())
        };
        mesh(case).map_err(|e| meshes::blame_uniform(case, e, |c| mesh(&c).map(drop)))
    }

    /// [`Model::build`] on a given mesh (`None`: the case's), one that an
    /// adaptive run refined from `Model::mesh_of`; a given mesh is checked
    /// like the case's own.
    pub fn build_on(case: Case, given: Option<Adapted>) -> Result<Model> {
        // a refusal of the case's own mesh may be `--uniform`'s
        let ungraded =
            (given.is_none() && case.overrides.graded_blocks.is_some()).then(|| case.clone());
        Model::assemble(case, given).map_err(|e| match ungraded {
            Some(case) => meshes::blame_uniform(&case, e, |c| Model::assemble(c, None).map(drop)),
            None => e,
        })
    }

    /// [`Model::build_on`], whoever is to blame.
    fn assemble(case: Case, given: Option<Adapted>) -> Result<Model> {
        let place = case.source.display().to_string();
        let checked = check_case(&case)?;
        let discs = given.as_ref().and_then(|g| g.excluded.clone());
        let (mut mesh, start_nodes) = start_mesh(&case, given, &place)?;
        let hanging_nodes = crate::input::mesh::refine::hanging_nodes(&mesh);
        let mut sections = crate::model::pretension::cut(&case, &mut mesh, &place)?;
        let plane = case.model.plane;
        let thickness = case.model.thickness.value();
        let section = crate::physics::element::Section {
            axisymmetric: plane == Plane::Axisymmetric,
            thickness,
        };
        let (rules, rules3) = gauss_rules(case.model.integration);
        // each node's original across the cuts; the start mesh's nodes (and
        // their copies): where a [[force]] acts and the probe is read on
        // every adaptive cycle
        let origin = crate::model::pretension::origins(&sections, mesh.nodes.len());
        let start: Vec<bool> = origin.iter().map(|&o| o < start_nodes).collect();
        let materials = materials(&case, &mesh, &place)?;
        check_elements(&mesh, (&rules, &rules3), &section, &place)?;
        let mut cyclic = cyclic::build(&case, &mesh, &place)?;
        let mut interfaces = interface_models(&case, &checked, &mesh, section, &place)?;
        let mut loads = crate::model::loads::build(&case, &mesh, &start, section, &place)?;
        let f_ext = loads.patterns.remove(0).f;
        gap_histories(&mut interfaces, &loads);
        let prescribed = supports(&case, &mesh, cyclic.as_ref(), &mut loads, &place)?;
        finish_sections(&case, &mut sections, &mesh, &loads);
        let n_dofs = crate::model::pretension::total_dofs(&case, &mesh);
        let held = Held {
            case: &case,
            place: &place,
            mesh: &mesh,
            sections: &sections,
            prescribed: &prescribed,
            loads: &loads,
            interfaces: &interfaces,
        };
        let constraints = held.constraints(&hanging_nodes, cyclic.as_mut(), n_dofs)?;
        held.check(&f_ext, section.axisymmetric, &constraints)?;
        let dofs = dof_map(n_dofs, &prescribed, &constraints);
        let (blocks, interface_block_base, expansions) =
            block_dofs(&mesh, &interfaces, &constraints, &sections);
        let section_block_base = blocks.len() - sections.len();
        drop(blocks);
        let (probe_node, surface_y) = probe(&case, &mesh, &start, &interfaces);
        let plan =
            crate::model::outputs::Plan::build(&case, &mesh, &interfaces, &prescribed, &place)?;
        let force_floor = force_floor(&mesh, &materials, section);
        let singular = singular::of_case(&case, &mesh, &origin);
        let mut model = Model {
            name: case.display_name(),
            plane,
            thickness,
            section,
            symmetric_half: case.model.symmetric_half,
            gauss_offsets: gauss_offsets(&mesh, (&rules, &rules3)),
            rules,
            rules3,
            materials,
            interfaces,
            prescribed,
            prescribed_history: loads.prescribed_history,
            f_ext,
            loads: loads.patterns,
            histories: loads.histories,
            temperatures: loads.temperatures,
            speed: loads.speed,
            applied: loads.applied,
            ratings: case.rating.clone(),
            applied_components: loads.components,
            dofs,
            interface_block_base,
            n_dofs,
            constraints,
            cyclic,
            expansions,
            sections,
            singular,
            excluded: None,
            section_block_base,
            probe_node,
            surface_y,
            force_floor,
            mesh,
            solver: case.solver.clone(),
            output: case.output.clone(),
            plan,
            source: case.source.clone(),
            overrides: case.overrides.clone(),
            description: case.description.clone(),
            integration: case.model.integration,
            case_key: case.key(),
        };
        if let Some(a) = &case.adapt {
            model.excluded = excluded_points(&model, a, discs);
            measurable::check(&model, a, &place)?;
        }
        Ok(model)
    }

    /// The dof lists of every element, then every interface point (rebuilt
    /// on demand: only the serial backend keeps per-block data).
    pub fn blocks(&self) -> Blocks {
        block_dofs(
            &self.mesh,
            &self.interfaces,
            &self.constraints,
            &self.sections,
        )
        .0
    }

    /// The diagonal of a held equation ([`crate::model::constraint`]): its row and
    /// column are otherwise zero, so any positive value leaves every other
    /// unknown exact; one of the model's scale, E_max × the model's diagonal
    /// × its out-of-plane measure (N/mm), from [`Model::force_floor`] (no
    /// pass over the nodes in the assembly).
    pub(crate) fn held_stiffness(&self) -> f64 {
        1e6 * self.force_floor
    }

    /// Every dof: the mesh's, then the pretension sections' reference nodes.
    pub fn num_dofs(&self) -> usize {
        self.n_dofs
    }

    /// Sets the constraints again after a change of the mesh, the
    /// prescribed dofs or the constraints themselves (tests): the dof map
    /// and the blocks' expansions follow.
    pub fn set_constraints(
        &mut self,
        list: Vec<crate::model::constraint::Constraint>,
    ) -> Result<()> {
        self.n_dofs = crate::model::pretension::total_dofs_of(&self.mesh, self.sections.len());
        self.constraints = crate::model::constraint::Constraints::new(list, self.n_dofs)
            .map_err(|m| Error::input(self.source.display().to_string(), m))?;
        self.dofs = dof_map(self.n_dofs, &self.prescribed, &self.constraints);
        let (blocks, base, expansions) = block_dofs(
            &self.mesh,
            &self.interfaces,
            &self.constraints,
            &self.sections,
        );
        self.section_block_base = blocks.len() - self.sections.len();
        self.interface_block_base = base;
        self.expansions = expansions;
        Ok(())
    }

    /// The dofs whose value follows from the others, set from them in `u`
    /// at pseudo-time t: the constraints' slaves.
    pub(crate) fn fill_slaves(&self, u: &mut [f64], t: f64) {
        self.constraints.fill(u, |h| self.factor(h, t));
    }

    /// The dofs held at pseudo-time t (a step to t): the shortening of
    /// every pretension section locked before t.
    pub(crate) fn held_dofs(&self, t: f64) -> Vec<usize> {
        self.sections
            .iter()
            .filter(|s| t > s.lock_after)
            .map(|s| s.dof)
            .collect()
    }

    /// Sparsity of the tangent over the free equations, every potential contact
    /// coupling included (built on demand, O(nonzeros): the serial backend
    /// builds it once and keeps what it needs).
    pub fn pattern(&self) -> Pattern {
        Pattern::new(&self.dofs, &self.blocks())
    }

    /// The columns of [`Model::pattern`] that `keep` selects (one PETSc
    /// rank's equations), the others empty.
    #[cfg(feature = "parallel")]
    pub(crate) fn pattern_of(&self, keep: impl Fn(usize) -> bool) -> Pattern {
        Pattern::columns(&self.dofs, &self.blocks(), keep)
    }

    /// Gauss point geometry of element e (checked valid when the model was built).
    pub fn geometry(&self, e: usize) -> ElementGeometry {
        let family = self.mesh.elements[e].family;
        let coords = self.mesh.element_coords(e);
        ElementGeometry::with_section(family, &coords, self.rule(e), &self.section)
            .expect("element geometry was checked when the model was built")
    }

    /// The Gauss point geometry of element e, plane or solid.
    pub(crate) fn element_geometry(&self, e: usize) -> crate::physics::element::Geometry {
        use crate::physics::element::Geometry;
        match self.mesh.elements[e].family.dim() {
            3 => Geometry::Solid(self.geometry3(e)),
            _ => Geometry::Plane(self.geometry(e)),
        }
    }

    /// Where Gauss point `ip` of element e is, in space (z = 0 in a plane
    /// model).
    pub fn point_x(&self, e: usize, ip: usize) -> [f64; 3] {
        self.element_geometry(e).x(ip)
    }

    /// Gauss point geometry of element e of a 3D mesh (checked valid when
    /// the model was built).
    pub(crate) fn geometry3(&self, e: usize) -> ElementGeometry3 {
        let family = self.mesh.elements[e].family;
        let solid = family.solid().expect("a 3D model's element");
        let coords = self.mesh.element_coords3(e);
        ElementGeometry3::new(solid, &coords[..family.nodes()], self.rule3(solid))
            .expect("element geometry was checked when the model was built")
    }

    /// The Gauss rule of a solid family's elements.
    pub(crate) fn rule3(&self, family: Family3) -> &GaussRule3 {
        &self.rules3[Family::from(family).index() - 2]
    }

    /// The dofs of the model's largest element (a slot of the element loop's
    /// buffers).
    pub(crate) fn max_element_dofs(&self) -> usize {
        let nodes = match self.mesh.dim() {
            3 => crate::physics::element::family::MAX_ELEMENT_NODES,
            _ => crate::physics::element::family::MAX_NODES,
        };
        self.node_dofs().element(nodes)
    }

    /// Element e's Gauss rule (a plane element).
    pub fn rule(&self, e: usize) -> &GaussRule {
        self.rule_of(self.mesh.elements[e].family)
    }

    /// Gauss points per element of a family, plane or solid.
    pub(crate) fn points_of(&self, family: Family) -> usize {
        match family.solid() {
            Some(solid) => self.rule3(solid).points.len(),
            None => self.rule_of(family).points.len(),
        }
    }

    /// The Gauss rule of a family's elements.
    pub(crate) fn rule_of(&self, family: Family) -> &GaussRule {
        &self.rules[family.index()]
    }

    /// The positions of element e's Gauss point states in a state vector.
    pub fn points(&self, e: usize) -> std::ops::Range<usize> {
        self.gauss_offsets[e]..self.gauss_offsets[e + 1]
    }

    /// The elements of `held` (ascending) with the positions of their Gauss
    /// point states in a state vector that holds theirs only, in order (one
    /// process holds every element: the positions are [`Model::points`]).
    pub(crate) fn held_points<'a>(
        &'a self,
        held: &'a [u32],
    ) -> impl Iterator<Item = (usize, std::ops::Range<usize>)> + 'a {
        let mut at = 0;
        held.iter().map(move |&e| {
            let e = e as usize;
            let n = self.points(e).len();
            at += n;
            (e, at - n..at)
        })
    }

    /// Replaces the mesh's elements and their Gauss point layout together
    /// (a model posed by hand, in tests: the layout follows the elements).
    pub fn set_elements(&mut self, elements: Vec<crate::input::mesh::Element>) {
        self.mesh.elements = elements;
        self.gauss_offsets = gauss_offsets(&self.mesh, (&self.rules, &self.rules3));
    }

    /// The element owning Gauss point state `i` (`i` < [`Model::n_points`]).
    pub(crate) fn element_of_point(&self, i: usize) -> usize {
        self.gauss_offsets.partition_point(|&o| o <= i) - 1
    }

    /// Whether the assembled tangent is symmetric, as the model's laws make
    /// it: the solids' tangents (elastic, continuum and consistent von Mises
    /// with associative flow) and the normal springs are; a tangential law
    /// makes it unsymmetric under the return-mapping scheme (p_T depends on
    /// p_N, eq. 2.18-2.21) but not under stiffness modification (eq. 2.25,
    /// no p_T-p_N coupling). Chooses the serial factorization.
    pub fn symmetric_tangent(&self) -> bool {
        self.interfaces.iter().all(|i| i.symmetric_tangent())
    }

    /// Pseudo-times of every history breakpoint, ascending: where the load
    /// path may turn (empty when the case has no history). With histories,
    /// 0 and 1 (the default ramp's points) are among them.
    pub fn breakpoints(&self) -> Vec<f64> {
        crate::model::history::breakpoints(&self.histories)
    }

    /// The value of every history of the case at pseudo-time t, in a fixed
    /// order (empty when the case has no history): two times with equal
    /// values have the same applied loads.
    pub fn history_values(&self, t: f64) -> Vec<f64> {
        self.histories.iter().map(|h| h.value(t)).collect()
    }

    /// The free thermal strain α ΔT h(t) of every body at pseudo-time t, in
    /// body order (0 for a body without a temperature).
    pub fn thermal_strains(&self, t: f64) -> Vec<f64> {
        (0..self.materials.len())
            .map(|b| self.thermal_strain(b, t))
            .collect()
    }

    /// Body `b`'s material at pseudo-time t: its Young's modulus and yield
    /// stress at its temperature there when its material has tables of them
    /// (`young_table`, `yield_table`), else the case's. Where a temperature
    /// field varies the material, this is its material at the field's
    /// factor 1; a point's is [`Model::material_point`].
    pub fn material_at(&self, b: usize, t: f64) -> VonMises {
        match self.temperatures.iter().find(|bt| bt.body == b) {
            Some(bt) => bt.material(&self.materials[b], self.factor(bt.history, t)),
            None => self.materials[b].clone(),
        }
    }

    /// Body `b`'s temperature load where its material varies from point to
    /// point (a field with a property table), else `None`.
    fn varying(&self, b: usize) -> Option<&crate::model::loads::thermal::BodyTemperature> {
        (self.temperatures.iter()).find(|bt| bt.body == b && bt.varies())
    }

    /// Body `b`'s material at pseudo-time t and point x: at the point's own
    /// temperature T_ref + ΔT h(t) f(x) where a temperature field varies it,
    /// else [`Model::material_at`].
    pub fn material_point(&self, b: usize, t: f64, x: [f64; 3]) -> VonMises {
        match self.varying(b) {
            Some(bt) => {
                let f = self.factor(bt.history, t) * bt.field_factor(x);
                bt.material(&self.materials[b], f)
            }
            None => self.material_at(b, t),
        }
    }

    /// The materials of body `b` at pseudo-time t at the points `x`: one for
    /// all where the body's material is uniform, else one per point
    /// ([`Model::material_point`]).
    pub fn point_materials(&self, b: usize, t: f64, x: &[[f64; 3]]) -> ElementMaterials {
        match self.varying(b) {
            Some(_) => ElementMaterials::PerPoint(
                x.iter().map(|&x| self.material_point(b, t, x)).collect(),
            ),
            None => ElementMaterials::Uniform(self.material_at(b, t)),
        }
    }

    /// The material of the model's Gauss point `i` (in [`Model::points`]
    /// numbering) at pseudo-time t ([`Model::material_point`]).
    pub fn gauss_material(&self, i: usize, t: f64) -> VonMises {
        let e = self.element_of_point(i);
        let b = self.mesh.elements[e].body;
        match self.varying(b) {
            Some(_) => self.material_point(b, t, self.point_x(e, i - self.gauss_offsets[e])),
            None => self.material_at(b, t),
        }
    }

    /// The materials of element e's Gauss points at pseudo-time t
    /// ([`Model::point_materials`] at the points of the model's rule).
    pub fn element_materials(&self, e: usize, t: f64) -> ElementMaterials {
        let b = self.mesh.elements[e].body;
        if self.varying(b).is_none() {
            return ElementMaterials::Uniform(self.material_at(b, t));
        }
        let geo = self.element_geometry(e);
        let x: Vec<[f64; 3]> = (0..geo.dv().len()).map(|ip| geo.x(ip)).collect();
        self.point_materials(b, t, &x)
    }

    /// What every body is at pseudo-time t: its free thermal strain and its
    /// material ([`Model::thermal_strain`], [`Model::material_at`]), and
    /// where a field varies the material, what each point's is read from
    /// (`Conditions::point_materials`).
    pub fn conditions(&self, t: f64) -> Conditions<'_> {
        let n = self.materials.len();
        let temperature = |b: usize| self.temperatures.iter().find(|bt| bt.body == b);
        Conditions {
            thermal: self.thermal_strains(t),
            materials: (0..n).map(|b| self.material_at(b, t)).collect(),
            fields: (0..n)
                .map(|b| temperature(b).and_then(|bt| bt.field.as_ref()))
                .collect(),
            varying: (0..n)
                .map(|b| {
                    self.varying(b).map(|bt| Varying {
                        temperature: bt,
                        factor: self.factor(bt.history, t),
                        base: &self.materials[b],
                    })
                })
                .collect(),
        }
    }

    /// The free thermal strain of body `body` at pseudo-time t and point x:
    /// α ΔT h(t), times its temperature field's factor at x where it has one.
    pub fn thermal_at(&self, body: usize, t: f64, x: [f64; 3]) -> f64 {
        let bt = self.temperatures.iter().find(|bt| bt.body == body);
        let f = bt
            .and_then(|bt| bt.field.as_ref())
            .map_or(1.0, |f| f.factor(x));
        self.thermal_strain(body, t) * f
    }

    /// The free thermal strain α ΔT h(t) of body `body` at pseudo-time t
    /// (the scale of its field where it has one: [`Model::thermal_at`]).
    pub fn thermal_strain(&self, body: usize, t: f64) -> f64 {
        self.temperatures
            .iter()
            .find(|bt| bt.body == body)
            .map_or(0.0, |bt| bt.strain * self.factor(bt.history, t))
    }

    /// The factor of a load with history `h` at pseudo-time t: the history's
    /// value; without one, t itself (a case without histories: the load
    /// factor) or the default ramp [[0, 0], [1, 1]] held at 1.
    pub fn factor(&self, h: Option<usize>, t: f64) -> f64 {
        match h {
            Some(i) => self.histories[i].value(t),
            None if self.histories.is_empty() => t,
            None => t.clamp(0.0, 1.0),
        }
    }

    /// Load `k` of [`Model::applied`] at pseudo-time t: its resultant force
    /// (N) and moment (N·mm) components.
    pub fn applied_at(&self, k: usize, t: f64) -> Vec<f64> {
        let a = &self.applied[k];
        let f = self.factor(a.history, t);
        a.resultant.iter().map(|r| f * r + 0.0).collect()
    }

    /// Every load pattern: how it scales and its forces at factor 1 (all
    /// dofs); [`Model::f_ext`] first, with no history of its own, the
    /// speed's centrifugal forces last.
    pub(crate) fn patterns(&self) -> impl Iterator<Item = (Scale, &[f64])> + '_ {
        std::iter::once((Scale::Factor(None), self.f_ext.as_slice()))
            .chain((self.loads.iter()).map(|p| (Scale::Factor(p.history), p.f.as_slice())))
            .chain((self.speed.iter()).map(|s| (Scale::Squared(s.history), s.f.as_slice())))
    }

    /// A pattern's factor at pseudo-time t.
    pub(crate) fn scale(&self, s: Scale, t: f64) -> f64 {
        match s {
            Scale::Factor(h) => self.factor(h, t),
            Scale::Squared(h) => self.factor(h, t).powi(2),
        }
    }

    /// The speed at pseudo-time t, rpm (`None`: the model does not spin).
    pub fn rpm(&self, t: f64) -> Option<f64> {
        (self.speed.as_ref()).map(|s| s.rpm * self.factor(s.history, t))
    }

    /// The external nodal forces at pseudo-time t (all dofs) into `out`:
    /// Σ_p h_p(t) f_p (the speed's h(t)² f), exactly t · f_ext in a case
    /// without histories.
    pub fn external_force(&self, t: f64, out: &mut [f64]) {
        for (k, (s, f)) in self.patterns().enumerate() {
            let a = self.scale(s, t);
            for (o, f) in out.iter_mut().zip(f) {
                *o = if k == 0 { a * f } else { *o + a * f };
            }
        }
    }

    /// The force applied to section `k`'s shortening at pseudo-time t (N):
    /// F h(t) for a force-controlled section, 0 for a prescribed shortening;
    /// the term of [`Model::external_force`] on its dof, summed alike.
    pub(crate) fn section_load(&self, k: usize, t: f64) -> f64 {
        let d = self.sections[k].dof;
        let mut f = self.factor(None, t) * self.f_ext[d];
        for p in &self.loads {
            f += self.factor(p.history, t) * p.f[d];
        }
        // a speed sets no force on a section's shortening: f[d] = 0
        f
    }

    /// What section `k` of a converged state at pseudo-time t reports
    /// (pretension.csv: force, shortening), from the force `across` its cut
    /// and the displacements `u`. While the section is free (force control,
    /// not yet locked, [`crate::model::pretension::free_at`]) its force is the
    /// applied F h(t), which its equation makes the force across the cut to
    /// Newton's tolerance: a value of the case, which a restart file cannot
    /// change ([`crate::files::restart`]).
    pub(crate) fn section_row(&self, k: usize, across: f64, u: &[f64], t: f64) -> [f64; 2] {
        let s = &self.sections[k];
        let force = if crate::model::pretension::free_at(s, t) {
            self.section_load(k, t)
        } else {
            across
        };
        [force, u[s.dof]]
    }

    /// The prescribed dofs and their values at pseudo-time t.
    pub(crate) fn prescribed_at(&self, t: f64) -> impl Iterator<Item = (usize, f64)> + '_ {
        self.prescribed
            .iter()
            .zip(&self.prescribed_history)
            .map(move |(&(d, v), &h)| (d, self.factor(h, t) * v))
    }

    /// The gap of interface `i` at pseudo-time t (mm): g₀, or g₀ · h(t)
    /// with a gap history.
    pub fn gap_at(&self, i: usize, t: f64) -> f64 {
        self.interfaces[i].gap_at(t)
    }

    /// The reference pressure of interface `i` in a step to pseudo-time t
    /// (MPa): the case's `start_pressure`, else the mean pressure of the
    /// applied load normal to the interface, at least 1 MPa; with no such
    /// load and an interference, the law's pressure at the interference.
    /// The secant start of eq. 2.8-2.9 and the contact stabilization's
    /// spring scale use it.
    pub fn reference_pressure(&self, i: usize, t: f64) -> f64 {
        let im = &self.interfaces[i];
        im.start_pressure.unwrap_or_else(|| {
            let p = self.applied_pressure(i, t);
            let gap = im.gap_at(t);
            if p == 0.0 && gap < 0.0 {
                im.law.pressure(-gap).0.max(1.0)
            } else {
                p.max(1.0)
            }
        })
    }

    /// The mean pressure of the applied loads on interface `i` at
    /// pseudo-time t (MPa): the resultant of the external forces along the
    /// interface's normal (at its first pair) over its area; 0 without such
    /// a load.
    pub(crate) fn applied_pressure(&self, i: usize, t: f64) -> f64 {
        let im = &self.interfaces[i];
        let n = im.pairs.first().map_or([0.0, 1.0, 0.0], |p| p.normal);
        let (nd, dim) = (self.mesh.node_dofs, self.mesh.dim());
        let normal = |f: &[f64]| -> f64 {
            (0..self.mesh.nodes.len())
                .map(|i| (0..dim).map(|c| f[nd.dof(i, c)] * n[c]).sum::<f64>())
                .sum()
        };
        if self.histories.is_empty() {
            // the load factor times the pattern's normal resultant, as always
            t * normal(&self.f_ext).abs() / im.area()
        } else {
            // the loads' (a speed's body force is no applied pressure)
            let f: f64 = (self.patterns())
                .filter(|(s, _)| matches!(s, Scale::Factor(_)))
                .map(|(s, f)| self.scale(s, t) * normal(f))
                .sum();
            f.abs() / im.area()
        }
    }

    /// Gauss points of the whole mesh (the length of a state vector).
    pub(crate) fn n_points(&self) -> usize {
        *self.gauss_offsets.last().unwrap_or(&0)
    }

    /// Dofs per node and their numbering (the mesh's [`NodeDofs`]).
    pub fn node_dofs(&self) -> NodeDofs {
        self.mesh.node_dofs
    }

    /// Element displacement vector, node-major: the first
    /// [`NodeDofs::element`] entries are used.
    pub fn element_u(&self, e: usize, u: &[f64]) -> ElementVector {
        let nd = self.mesh.node_dofs;
        let k = nd.per_node();
        let mut ue = [0.0; NodeDofs::MAX_ELEMENT];
        for (a, &n) in self.mesh.elements[e].nodes().iter().enumerate() {
            ue[k * a..k * (a + 1)].copy_from_slice(&u[nd.of(n)]);
        }
        ue
    }

    /// Factor from the half model's force (N) to kN per mm of thickness of the
    /// whole body; in axisymmetry, from the force of the full revolution (N) to kN.
    pub(crate) fn load_scale_kn(&self) -> f64 {
        if self.section.axisymmetric {
            return 1.0 / 1000.0;
        }
        let sym = if self.symmetric_half { 2.0 } else { 1.0 };
        sym / self.thickness / 1000.0
    }
}

/// Each plane family's and each solid family's Gauss rule at `integration`.
fn gauss_rules(integration: Integration) -> ([GaussRule; 2], [GaussRule3; 2]) {
    let full = integration == Integration::Full;
    (
        Family::ALL.map(|f| f.rule(full)),
        [Family3::H20, Family3::T10].map(|f| f.rule(full)),
    )
}

/// The dof map: prescribed dofs and the constraints' slaves have no equation.
fn dof_map(
    n_dofs: usize,
    prescribed: &[(usize, f64)],
    constraints: &crate::model::constraint::Constraints,
) -> DofMap {
    let mut mask = vec![false; n_dofs];
    for &(d, _) in prescribed {
        mask[d] = true;
    }
    for c in &constraints.list {
        mask[c.slave] = true;
    }
    DofMap::new(n_dofs, &mask)
}

/// Element and interface-point dof lists (a block that holds a slave dof:
/// its masters, with its expansion), then one block per pretension
/// section's reference node; and the index of each interface's first block.
fn block_dofs(
    mesh: &Mesh,
    interfaces: &[InterfaceModel],
    constraints: &crate::model::constraint::Constraints,
    sections: &[crate::model::pretension::Section],
) -> (
    Blocks,
    Vec<usize>,
    std::collections::HashMap<usize, crate::model::constraint::Expansion>,
) {
    let mut blocks = Blocks::new();
    let mut expansions = std::collections::HashMap::new();
    let mut push = |blocks: &mut Blocks, dofs: Vec<usize>| match constraints.expand(&dofs) {
        Some(x) => {
            blocks.push(x.dofs.iter().copied());
            expansions.insert(blocks.len() - 1, x);
        }
        None => blocks.push(dofs),
    };
    for el in &mesh.elements {
        push(
            &mut blocks,
            el.nodes()
                .iter()
                .flat_map(|&n| mesh.node_dofs.of(n))
                .collect(),
        );
    }
    let mut base = Vec::new();
    for im in interfaces {
        base.push(blocks.len());
        for p in &im.points {
            push(&mut blocks, im.point_dofs(p));
        }
    }
    for s in sections {
        blocks.push([s.dof, s.dof + 1]);
    }
    (blocks, base, expansions)
}

fn probe(case: &Case, mesh: &Mesh, start: &[bool], interfaces: &[InterfaceModel]) -> (usize, f64) {
    let p = case.output.probe;
    // a node that refinement added is never nearer: an adaptive run reads
    // the same node on every mesh (a start mesh node, [`Adapted`])
    let dist = |n: usize| {
        let x = mesh.nodes[n];
        if start[n] {
            (x[0] - p[0]).hypot(x[1] - p[1])
        } else {
            f64::INFINITY
        }
    };
    // body B's interface nodes: the pairs' B nodes, and every node of the
    // master side of a non-matching interface (mortar gives a slave node on
    // the axis no pair, so the pairs alone may miss the node under the probe)
    let master = mesh
        .interfaces
        .iter()
        .filter_map(|i| i.nonmatching.as_ref())
        .flat_map(|nm| nm.master.iter().flatten().copied());
    let best = interfaces
        .iter()
        .flat_map(|im| im.pairs.iter().map(|pr| pr.b))
        .chain(master)
        .min_by(|&a, &b| dist(a).total_cmp(&dist(b)))
        .unwrap_or_else(|| {
            (0..mesh.nodes.len())
                .min_by(|&a, &b| dist(a).total_cmp(&dist(b)))
                .unwrap_or(0)
        });
    (best, mesh.nodes.get(best).map_or(0.0, |x| x[1]))
}

/// The material of every body, in body order; a body without
/// `[materials.<body>]` and an entry without a body are refused.
fn materials(case: &Case, mesh: &Mesh, place: &str) -> Result<Vec<VonMises>> {
    let mut materials = Vec::new();
    for body in &mesh.bodies {
        let spec = case.materials.get(body).ok_or_else(|| {
            Error::input(
                place,
                format!("[materials] has no entry for body \"{body}\""),
            )
        })?;
        let mat = VonMises::new(
            spec.young,
            spec.poisson,
            spec.yield_stress.unwrap_or(f64::INFINITY),
            spec.hardening,
            case.model.plane,
        )
        .map_err(|e| Error::input(format!("{place}: [materials.{body}]"), e))?;
        materials.push(mat);
    }
    for name in case.materials.keys() {
        if !mesh.bodies.contains(name) {
            return Err(Error::input(
                format!("{place}: [materials.{name}]"),
                format!(
                    "no body named \"{name}\" (bodies: {})",
                    mesh.bodies.join(", ")
                ),
            ));
        }
    }
    Ok(materials)
}

/// Every element's Jacobian, checked once; the geometry itself is
/// recomputed when needed ([`Model::geometry`]).
fn check_elements(
    mesh: &Mesh,
    (rules, rules3): (&[GaussRule; 2], &[GaussRule3; 2]),
    section: &crate::physics::element::Section,
    place: &str,
) -> Result<()> {
    for (e, el) in mesh.elements.iter().enumerate() {
        let checked = match el.family.solid() {
            None => {
                let rule = &rules[el.family.index()];
                let coords = mesh.element_coords(e);
                ElementGeometry::with_section(el.family, &coords, rule, section).map(drop)
            }
            Some(solid) => {
                let rule = &rules3[el.family.index() - 2];
                let coords = mesh.element_coords3(e);
                ElementGeometry3::new(solid, &coords[..el.family.nodes()], rule).map(drop)
            }
        };
        checked.map_err(|m| Error::Mesh {
            place: place.to_string(),
            message: format!(
                "{} of body \"{}\": {m}",
                mesh.element_label(e),
                mesh.bodies[el.body]
            ),
        })?;
    }
    Ok(())
}

/// Where each element's Gauss point states start in a state vector (and,
/// last, their total): elements in order, each its family's rule.
fn gauss_offsets(mesh: &Mesh, (rules, rules3): (&[GaussRule; 2], &[GaussRule3; 2])) -> Vec<usize> {
    let mut offsets = Vec::with_capacity(mesh.elements.len() + 1);
    let mut at = 0;
    offsets.push(at);
    for el in &mesh.elements {
        at += match el.family.dim() {
            3 => rules3[el.family.index() - 2].points.len(),
            _ => rules[el.family.index()].points.len(),
        };
        offsets.push(at);
    }
    offsets
}

/// The interface models, one per mesh interface with its checked law; an
/// `[interface.<name>]` without a mesh interface is refused.
fn interface_models(
    case: &Case,
    checked: &crate::input::case::Checked,
    mesh: &Mesh,
    section: crate::physics::element::Section,
    place: &str,
) -> Result<Vec<InterfaceModel>> {
    let mut interfaces = Vec::new();
    for iface in &mesh.interfaces {
        let law = checked.laws.get(&iface.name).ok_or_else(|| {
            Error::input(
                place,
                format!(
                    "[interface] has no law for interface \"{0}\": add [interface.{0}] with its law (e.g. law = \"power\", c_n, m)",
                    iface.name
                ),
            )
        })?;
        let spec = &case.interface[&iface.name];
        let mut im = InterfaceModel::new(
            mesh,
            iface,
            law.clone(),
            spec.gap,
            spec.weights,
            section,
            spec.start_pressure,
            checked.tangential.get(&iface.name).cloned(),
        )
        .map_err(|m| Error::input(place, m))?;
        if let Some(p) = &spec.moment_point {
            im.moment_point = [p[0], p[1], p[2]];
        }
        interfaces.push(im);
    }
    for name in case.interface.keys() {
        if !mesh.interfaces.iter().any(|i| &i.name == name) {
            return Err(Error::input(
                format!("{place}: [interface.{name}]"),
                format!("the mesh has no interface named \"{name}\""),
            ));
        }
    }
    Ok(interfaces)
}

/// The Gauss points an adaptive run on `max_von_mises` leaves out: in the
/// discs an adapted mesh carries from the start mesh (`discs`), or, on the
/// start mesh, about its own singular points ([`excluded`]); None for
/// another quantity.
fn excluded_points(
    model: &Model,
    spec: &crate::input::case::adapt::AdaptSpec,
    discs: Option<Vec<excluded::Disc>>,
) -> Option<excluded::Excluded> {
    (spec.quantity == crate::input::case::adapt::Quantity::MaxVonMises).then(|| {
        let discs =
            discs.unwrap_or_else(|| model.singular.iter().map(excluded::Disc::about).collect());
        excluded::Excluded::on(model, discs)
    })
}

/// The mesh a model is built on, and the number of nodes of the run's start
/// mesh: the case's own (generated or read) or an adaptive cycle's `given`,
/// with the twist's dofs; refuses a start mesh above `[adapt] max_dofs`.
fn start_mesh(case: &Case, given: Option<Adapted>, place: &str) -> Result<(Mesh, usize)> {
    let (mut mesh, start_nodes) = match given {
        None => {
            let mesh = make_mesh(case, place)?;
            let n = mesh.nodes.len();
            (mesh, n)
        }
        Some(a) => (check_mesh(case, a.mesh, place)?, a.start_nodes),
    };
    if case.model.twist {
        mesh.node_dofs = NodeDofs::TWIST;
    }
    if mesh.dim() == 3 {
        mesh.node_dofs = NodeDofs::SOLID;
    }
    // an adaptive run builds its start mesh here too (given, as every
    // cycle's); it never refines past the cap, so only that one can fail
    if let Some(a) = case.adapt.as_ref().filter(|a| mesh.num_dofs() > a.max_dofs) {
        // the cap of `--adapt` (its default) or the file's; the mesh
        // perhaps of `--refine`
        let cap = match case.option("[adapt] max_dofs") {
            Some(_) => format!("its default max_dofs ({})", a.max_dofs),
            None => a.max_dofs.to_string(),
        };
        let refined = case
            .option("[mesh] refine")
            .map_or(String::new(), |o| format!(" (of {o})"));
        return Err(Error::input(
            case.at("[adapt] max_dofs"),
            format!(
                "{cap} is below the {} dofs of the start mesh{refined}: not even the first mesh may be solved",
                mesh.num_dofs()
            ),
        ));
    }
    Ok((mesh, start_nodes))
}

/// Gives each pretension section its dof and the end of its locking (the end
/// of its history, or of the run's).
/// Each interface's gap history (`gap_history`), from the loads' histories.
fn gap_histories(interfaces: &mut [InterfaceModel], loads: &crate::model::loads::Loads) {
    for im in interfaces.iter_mut() {
        im.gap_history = loads
            .gap_history
            .get(&im.name)
            .map(|&h| loads.histories[h].clone());
    }
}

fn finish_sections(
    case: &Case,
    sections: &mut [crate::model::pretension::Section],
    mesh: &Mesh,
    loads: &crate::model::loads::Loads,
) {
    let lock_end: Vec<Option<f64>> = loads
        .pretension_history
        .iter()
        .map(|&h| match h {
            Some(h) => Some(loads.histories[h].end()),
            None if loads.histories.is_empty() => None,
            None => Some(1.0),
        })
        .collect();
    crate::model::pretension::finish(case, sections, mesh.node_dofs, mesh.nodes.len(), &lock_end);
}

/// What holds and loads a model, as [`Model::assemble`] has built it: the
/// constraints are made from it and its consistency checked.
struct Held<'a> {
    case: &'a Case,
    place: &'a str,
    mesh: &'a Mesh,
    sections: &'a [crate::model::pretension::Section],
    prescribed: &'a [(usize, f64)],
    loads: &'a crate::model::loads::Loads,
    interfaces: &'a [InterfaceModel],
}

impl Held<'_> {
    /// The constraints of the pretension sections, the hanging nodes and a
    /// cyclic sector's ties (counting the ties the supports hold alike)
    /// over `n_dofs` dofs.
    fn constraints(
        &self,
        hanging_nodes: &[crate::input::mesh::refine::HangingNode],
        cyclic: Option<&mut crate::model::cyclic::Cyclic>,
        n_dofs: usize,
    ) -> Result<crate::model::constraint::Constraints> {
        let (mesh, sections, prescribed, loads, place) = (
            self.mesh,
            self.sections,
            self.prescribed,
            self.loads,
            self.place,
        );
        let mut list = crate::model::pretension::constraints(
            mesh.node_dofs,
            &mesh.nodes,
            sections,
            prescribed,
            &loads.prescribed_history,
            place,
        )?;
        list.extend(hanging::constraints(
            mesh,
            hanging_nodes,
            prescribed,
            &loads.prescribed_history,
            sections,
            place,
        )?);
        if let Some(c) = cyclic {
            let (ties, alike) = crate::model::cyclic::ties(
                c,
                self.case,
                mesh,
                prescribed,
                &loads.prescribed_history,
                place,
            )?;
            c.held_alike = alike;
            list.extend(ties);
        }
        crate::model::constraint::Constraints::new(list, n_dofs).map_err(|m| Error::input(place, m))
    }

    /// Checks that the loads act where they can, that something loads the
    /// model, and that the supports hold its bodies, its sections and, on a
    /// symmetric half, the symmetry plane.
    fn check(
        &self,
        f_ext: &[f64],
        axisymmetric: bool,
        constraints: &crate::model::constraint::Constraints,
    ) -> Result<()> {
        let (case, mesh, sections, prescribed, loads, interfaces, place) = (
            self.case,
            self.mesh,
            self.sections,
            self.prescribed,
            self.loads,
            self.interfaces,
            self.place,
        );
        crate::model::loads::check_acting(&loads.acting, mesh, prescribed, axisymmetric)?;
        check_loaded(f_ext, loads, prescribed, interfaces, place)?;
        let ties = &constraints.list;
        check_supports(mesh, prescribed, ties, interfaces, axisymmetric, place)?;
        supports::check_sections_held(mesh, sections, prescribed, interfaces, place)?;
        let tied: std::collections::HashMap<usize, usize> = sections
            .iter()
            .flat_map(|s| s.pairs.iter().map(|&(n, c)| (c, n)))
            .collect();
        whole::check_symmetry_supports(case, mesh, prescribed, &tied, place)?;
        Ok(())
    }
}

/// The prescribed dofs with u_r = 0 added on the axis of an axisymmetric
/// model, u_x = u_z = 0 on the axis of a cyclic sector (no history: always
/// 0); `loads.prescribed_history` follows them.
fn supports(
    case: &Case,
    mesh: &Mesh,
    cyclic: Option<&crate::model::cyclic::Cyclic>,
    loads: &mut crate::model::loads::Loads,
    place: &str,
) -> Result<Vec<(usize, f64)>> {
    let given: std::collections::HashMap<usize, Option<usize>> = loads
        .prescribed
        .iter()
        .zip(&loads.prescribed_history)
        .map(|(&(d, _), &h)| (d, h))
        .collect();
    let prescribed =
        crate::model::axis::hold_axis(case, mesh, std::mem::take(&mut loads.prescribed), place)?;
    let prescribed = cyclic::hold_axis(cyclic, case, mesh, prescribed, place)?;
    loads.prescribed_history = prescribed
        .iter()
        .map(|(d, _)| given.get(d).copied().flatten())
        .collect();
    Ok(prescribed)
}

/// Something must load the model: a load, a force, a non-zero prescribed
/// displacement or an interference.
fn check_loaded(
    f_ext: &[f64],
    loads: &crate::model::loads::Loads,
    prescribed: &[(usize, f64)],
    interfaces: &[InterfaceModel],
    place: &str,
) -> Result<()> {
    let interference = interfaces
        .iter()
        .any(|im| im.gap < 0.0 || (im.gap != 0.0 && im.gap_history.is_some()));
    if f_ext.iter().all(|&f| f == 0.0)
        && loads.patterns.iter().all(|p| p.f.iter().all(|&f| f == 0.0))
        && prescribed.iter().all(|&(_, v)| v == 0.0)
        && !interference
        && loads.temperatures.iter().all(|t| t.strain == 0.0)
        && loads.speed.is_none()
    {
        return Err(Error::input(
            place,
            "nothing loads the model: no [[load]], no [[force]], no non-zero prescribed displacement in [[boundary]], no interference (negative gap) or gap_history, no [[temperature]] and no [speed]",
        ));
    }
    Ok(())
}

/// The force below which a residual is zero: 10⁻⁶ E_max × the model's
/// diagonal × its out-of-plane measure (the thickness, or the outer
/// circumference 2π r_max in axisymmetry).
fn force_floor(
    mesh: &Mesh,
    materials: &[VonMises],
    section: crate::physics::element::Section,
) -> f64 {
    let e_max = materials.iter().fold(0.0f64, |a, m| a.max(m.young));
    let (lo, hi) = mesh
        .nodes
        .iter()
        .fold(([f64::MAX; 2], [f64::MIN; 2]), |(lo, hi), x| {
            (
                [lo[0].min(x[0]), lo[1].min(x[1])],
                [hi[0].max(x[0]), hi[1].max(x[1])],
            )
        });
    let measure = if section.axisymmetric {
        section.measure(hi)
    } else {
        section.thickness
    };
    1e-6 * e_max * (hi[0] - lo[0]).hypot(hi[1] - lo[1]) * measure
}
