#include <drape/garment/sizing_drape.hpp>

#include <drape/cloth/obstacle.hpp>
#include <drape/cloth/simulator.hpp>
#include <drape/core/errors.hpp>

#include "drape_run.hpp"

#include <chrono>
#include <cmath>
#include <optional>
#include <utility>

namespace drape::garment {

bool SizingDrapeOptions::is_valid(std::string* why) const {
    const auto fail = [&](const std::string& what) {
        if (why) *why = what;
        return false;
    };
    std::string reason;
    if (!drape.is_valid(&reason)) return fail("SizingDrapeOptions::drape: " + reason);
    if (!(time_step_s >= 0 && std::isfinite(time_step_s)))
        return fail(drape::detail::concat("SizingDrapeOptions::time_step_s = ", time_step_s, " must be >= 0"));
    if (max_steps < 1) return fail(drape::detail::concat("SizingDrapeOptions::max_steps = ", max_steps, " must be >= 1"));
    if (body_blend_steps < 1)
        return fail(drape::detail::concat("SizingDrapeOptions::body_blend_steps = ", body_blend_steps, " must be >= 1"));
    if (min_steps < 0 || min_steps > max_steps)
        return fail(drape::detail::concat("SizingDrapeOptions::min_steps = ", min_steps, " must be in [0, max_steps = ",
                                   max_steps, "]"));
    if (!(settled_kinetic_energy_j_per_kg > 0))
        return fail(drape::detail::concat("SizingDrapeOptions::settled_kinetic_energy_j_per_kg = ",
                                   settled_kinetic_energy_j_per_kg, " must be > 0"));
    return true;
}

bool SizingDrapeResult::usable(const DrapeOptions& tolerances) const {
    return converged && seam_gap_max_m < tolerances.seam_gap_tolerance_m &&
           penetration_max_m <= tolerances.penetration_tolerance_m && self_intersections == 0;
}

// Read-only after construction, shared by copies.
struct SizingDrape::Shared {
    SizingDrapeOptions options;
    Pattern pattern;
    GarmentSizing sizing;
    PatternMorph morph;
    Eigen::MatrixX3d base_positions;   // garment vertices
    cloth::ClothMesh sim_mesh;         // welded (or not) at the base drape
    std::vector<int> vertex_of;        // garment vertex -> simulation vertex
    bool welded = false;
    std::vector<cloth::Stitch> stitches;  // when not welded
    std::vector<int> face_material;       // 0 fabric, 1 waistband
    std::optional<cloth::Obstacle> body;
};

struct SizingDrape::State {
    cloth::Simulator sim;
    GarmentSizing sizing;
    cloth::Material material;
    Eigen::MatrixX3d last_settled;  // simulation vertices; empty until one settled
    Eigen::MatrixX3d body;          // the body to move to (set_body); empty: the base body
};

namespace {

std::vector<cloth::Material> fabrics(const cloth::Material& m, const DrapeOptions& o) {
    return {m, waistband_material(m, o.waistband_stretching_factor)};
}

}  // namespace

SizingDrape::SizingDrape(const Pattern& pattern, const GarmentSizing& sizing, const GarmentMesh& mesh,
                         const Eigen::MatrixX3d& draped, const Eigen::MatrixX3d& body_vertices,
                         const Eigen::MatrixX3i& body_faces, const cloth::Material& material,
                         const SizingDrapeOptions& options) {
    std::string why;
    require(options.is_valid(&why), "SizingDrape: ", why);
    require(material.is_valid(&why), "SizingDrape: material: ", why);
    const int nv = mesh.cloth.vertex_count();
    require(draped.rows() == nv && draped.allFinite(), "SizingDrape: the drape has ", draped.rows(),
            " rows (need the mesh's ", nv, ", all finite)");
    require(body_vertices.rows() > 0 && body_vertices.allFinite(), "SizingDrape: the body has ", body_vertices.rows(),
            " vertices (need > 0, all finite)");
    auto shared = std::make_shared<Shared>(Shared{options, pattern, sizing, PatternMorph(pattern, mesh), draped, {}, {},
                                                  false, {}, {}, std::nullopt});
    Shared& s = *shared;
    s.body.emplace(body_vertices, body_faces);
    s.face_material.assign(size_t(mesh.cloth.face_count()), 0);
    for (int f : waistband_faces(pattern, mesh, options.drape.waistband_width_cm)) s.face_material[size_t(f)] = 1;
    // As the drape: the seams welded (one vertex per stitched group), else stitches.
    if (options.drape.weld_seams && !mesh.stitches.empty()) {
        Eigen::MatrixX3d v;
        detail::Welded w =
            detail::weld(mesh.cloth, draped, Eigen::MatrixX3d::Zero(nv, 3), mesh.stitches, &v);
        try {
            w.mesh.validate();
            s.sim_mesh = std::move(w.mesh);
            s.vertex_of = std::move(w.vertex_of);
            s.welded = true;
        } catch (const InvalidInput&) {
            s.welded = false;  // as drape_garment: a mesh that cannot be welded keeps its stitches
        }
    }
    if (!s.welded) {
        s.sim_mesh = mesh.cloth;
        s.sim_mesh.positions = draped;
        s.vertex_of.resize(size_t(nv));
        for (int v = 0; v < nv; ++v) s.vertex_of[size_t(v)] = v;
        s.stitches = garment_stitches(mesh);
    }
    cloth::SimulatorOptions sim_options = options.drape.simulator;
    if (options.time_step_s > 0) sim_options.time_step_s = options.time_step_s;
    cloth::Simulator sim(s.sim_mesh, fabrics(material, options.drape), s.face_material, sim_options);
    sim.set_obstacle(*s.body);
    if (!s.welded) sim.set_stitches(s.stitches);
    shared_ = std::move(shared);
    state_ = std::make_unique<State>(State{std::move(sim), sizing, material, {}, {}});
}

namespace {

void require_garment(const DressedOutfit& outfit, int garment) {
    require(garment >= 0 && size_t(garment) < outfit.positions.size() && size_t(garment) < outfit.meshes.size() &&
                size_t(garment) < outfit.patterns.size() && size_t(garment) < outfit.sizings.size(),
            "SizingDrape: garment ", garment, " is out of range [0, ", outfit.positions.size(), ")");
}

}  // namespace

SizingDrape::SizingDrape(const DressedOutfit& outfit, int garment, const Eigen::MatrixX3i& body_faces,
                         const cloth::Material& material, const SizingDrapeOptions& options)
    : SizingDrape((require_garment(outfit, garment), outfit.patterns[size_t(garment)]), outfit.sizings[size_t(garment)],
                  outfit.meshes[size_t(garment)], outfit.positions[size_t(garment)], outfit.body_vertices, body_faces,
                  material, options) {}

SizingDrape::~SizingDrape() = default;
SizingDrape::SizingDrape(SizingDrape&&) noexcept = default;
SizingDrape& SizingDrape::operator=(SizingDrape&&) noexcept = default;

SizingDrape::SizingDrape(const SizingDrape& other) : shared_(other.shared_) {
    const State& o = *other.state_;
    // A simulator of its own with the other's rest shape, fabric and state.
    cloth::Simulator sim(o.sim.mesh(), o.sim.materials(), o.sim.face_material(), o.sim.options());
    sim.set_obstacle(*o.sim.obstacle());
    if (!shared_->welded) sim.set_stitches(o.sim.stitches());
    state_ = std::make_unique<State>(State{std::move(sim), o.sizing, o.material, o.last_settled, o.body});
}

SizingDrape& SizingDrape::operator=(const SizingDrape& other) {
    if (this != &other) *this = SizingDrape(other);
    return *this;
}

SizingDrapeResult SizingDrape::evaluate(const GarmentSizing& g) {
    const Shared& s = *shared_;
    require(g.type == s.sizing.type, "SizingDrape::evaluate: the sizing is a ", garment_type_name(g.type),
            ", this drape is a ", garment_type_name(s.sizing.type));
    const auto t0 = std::chrono::steady_clock::now();
    // Everything that can refuse the sizing runs before the state changes.
    const GarmentMesh morphed = s.morph.morph(make_pattern(g));
    State& st = *state_;
    st.sim.set_rest_positions(morphed.cloth.pattern);
    st.sizing = g;
    SizingDrapeResult r = evaluate();
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
}

SizingDrapeResult SizingDrape::evaluate() {
    const Shared& s = *shared_;
    State& st = *state_;
    const SizingDrapeOptions& o = s.options;
    const auto t0 = std::chrono::steady_clock::now();
    const bool moved = st.body.rows() > 0;
    const bool from_last =
        !moved && o.warm_start == SizingDrapeOptions::WarmStart::last_settled && st.last_settled.size() > 0;
    st.sim.set_positions(from_last ? st.last_settled : s.sim_mesh.positions);
    st.sim.set_velocities(Eigen::MatrixX3d::Zero(st.sim.positions().rows(), 3));
    st.sim.move_obstacle(s.body->positions());
    const double mass = st.sim.masses().sum();
    const int blend = moved ? o.body_blend_steps : 0;
    SizingDrapeResult r;
    for (int k = 0; k < blend + o.max_steps; ++k) {
        if (k < blend) {
            const double t = double(k + 1) / blend;
            st.sim.move_obstacle((1.0 - t) * s.body->positions() + t * st.body);
        }
        const cloth::StepSummary step = st.sim.step();
        if (!step.usable()) {
            r.message = drape::detail::concat("step ", k + 1, ": ", step.brief_report());
            break;
        }
        ++r.steps;
        r.newton_iterations += step.newton_iterations;
        r.kinetic_energy_j_per_kg = detail::kinetic_energy(st.sim) / mass;
        if (k + 1 >= blend + o.min_steps && r.kinetic_energy_j_per_kg < o.settled_kinetic_energy_j_per_kg) {
            r.converged = true;
            break;
        }
    }
    if (!r.converged && r.message.empty())
        r.message = drape::detail::concat("not at rest after ", r.steps, " steps (kinetic energy ", r.kinetic_energy_j_per_kg,
                                   " J/kg)");
    if (r.converged) st.last_settled = st.sim.positions();
    const cloth::ContactReport c = st.sim.contact_report();
    r.penetration_max_m = c.max_penetration_m;
    r.seam_gap_max_m = c.max_stitch_gap_m;
    r.self_intersections = c.self_intersections;
    r.positions.resize(Eigen::Index(s.vertex_of.size()), 3);
    for (size_t v = 0; v < s.vertex_of.size(); ++v)
        r.positions.row(Eigen::Index(v)) = st.sim.positions().row(s.vertex_of[v]);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
}

void SizingDrape::set_material(const cloth::Material& material) {
    std::string why;
    require(material.is_valid(&why), "SizingDrape::set_material: ", why);
    state_->sim.set_materials(fabrics(material, shared_->options.drape));
    state_->material = material;
}

void SizingDrape::set_body(const Eigen::MatrixX3d& body_vertices) {
    const Eigen::MatrixX3d& base = shared_->body->positions();
    require(body_vertices.rows() == 0 || (body_vertices.rows() == base.rows() && body_vertices.allFinite()),
            "SizingDrape::set_body: the body has ", body_vertices.rows(), " vertices (need the base body's ",
            base.rows(), ", all finite, or none)");
    state_->body = body_vertices;
}

const GarmentSizing& SizingDrape::sizing() const { return state_->sizing; }
const cloth::Material& SizingDrape::material() const { return state_->material; }
const GarmentSizing& SizingDrape::base_sizing() const { return shared_->sizing; }
const Eigen::MatrixX3d& SizingDrape::base_positions() const { return shared_->base_positions; }
GarmentMesh SizingDrape::mesh() const { return shared_->morph.morph(make_pattern(state_->sizing)); }
const SizingDrapeOptions& SizingDrape::options() const { return shared_->options; }

}  // namespace drape::garment
