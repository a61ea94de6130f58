// The public facade of the simulator (drape/cloth/simulator.hpp): construction, pins,
// obstacle, stitches, time steps and the static solve. The parts live beside it (see
// simulator_impl.hpp).
#include <drape/cloth/simulator.hpp>

#include <drape/cloth/intersections.hpp>
#include <drape/core/errors.hpp>

#include "simulator_impl.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <utility>

namespace drape::cloth {

namespace {

const char* to_string(StepTermination t) {
    switch (t) {
        case StepTermination::converged: return "converged";
        case StepTermination::max_iterations: return "max_iterations";
        case StepTermination::line_search_failed: return "line_search_failed";
        case StepTermination::non_finite: return "non_finite";
        case StepTermination::cancelled: return "cancelled";
    }
    return "unknown";
}

}  // namespace

bool SimulatorOptions::is_valid(std::string* why) const {
    auto fail = [&](const std::string& reason) {
        if (why) *why = reason;
        return false;
    };
    auto nonneg = [](double v) { return std::isfinite(v) && v >= 0; };
    if (!(std::isfinite(time_step_s) && time_step_s > 0))
        return fail(detail::concat("time_step_s = ", time_step_s, " must be > 0"));
    if (!gravity_m_per_s2.allFinite()) return fail("gravity_m_per_s2 is not finite");
    if (!(std::isfinite(relative_tolerance) && relative_tolerance > 0))
        return fail(detail::concat("relative_tolerance = ", relative_tolerance, " must be > 0"));
    if (!(std::isfinite(step_relative_tolerance) && step_relative_tolerance > 0))
        return fail(detail::concat("step_relative_tolerance = ", step_relative_tolerance, " must be > 0"));
    if (!(std::isfinite(step_displacement_tolerance_m) && step_displacement_tolerance_m >= 0))
        return fail(detail::concat("step_displacement_tolerance_m = ", step_displacement_tolerance_m,
                                   " must be >= 0"));
    if (max_nonconvex_step_iterations < 0)
        return fail(detail::concat("max_nonconvex_step_iterations = ", max_nonconvex_step_iterations,
                                   " must be >= 0"));
    if (max_newton_iterations < 1)
        return fail(detail::concat("max_newton_iterations = ", max_newton_iterations, " must be >= 1"));
    if (max_step_halvings < 0 || max_step_halvings > 20)
        return fail(detail::concat("max_step_halvings = ", max_step_halvings, " must be in [0, 20]"));
    if (max_line_search_halvings < 0)
        return fail(detail::concat("max_line_search_halvings = ", max_line_search_halvings,
                                   " must be >= 0"));
    if (!(std::isfinite(static_damping_time_s) && static_damping_time_s > 0))
        return fail(detail::concat("static_damping_time_s = ", static_damping_time_s, " must be > 0"));
    if (!(std::isfinite(contact_thickness_m) && contact_thickness_m > 0))
        return fail(detail::concat("contact_thickness_m = ", contact_thickness_m, " must be > 0"));
    if (!(std::isfinite(contact_inside_stiffness_factor) && contact_inside_stiffness_factor >= 1))
        return fail(detail::concat("contact_inside_stiffness_factor = ", contact_inside_stiffness_factor,
                                   " must be >= 1"));
    if (!(std::isfinite(contact_stiffness_n_per_m3) && contact_stiffness_n_per_m3 > 0))
        return fail(detail::concat("contact_stiffness_n_per_m3 = ", contact_stiffness_n_per_m3,
                                   " must be > 0"));
    if (!nonneg(obstacle_friction))
        return fail(detail::concat("obstacle_friction = ", obstacle_friction, " must be >= 0"));
    if (!nonneg(cloth_friction))
        return fail(detail::concat("cloth_friction = ", cloth_friction, " must be >= 0"));
    if (!(std::isfinite(friction_slip_speed_m_per_s) && friction_slip_speed_m_per_s > 0))
        return fail(detail::concat("friction_slip_speed_m_per_s = ", friction_slip_speed_m_per_s,
                                   " must be > 0"));
    if (std::isnan(friction_majorize_slip_m) || friction_majorize_slip_m < 0)
        return fail(detail::concat("friction_majorize_slip_m = ", friction_majorize_slip_m,
                                   " must be >= 0 (infinity: the exact friction Hessian)"));
    if (!(std::isfinite(stitch_stiffness_n_per_m2) && stitch_stiffness_n_per_m2 > 0))
        return fail(detail::concat("stitch_stiffness_n_per_m2 = ", stitch_stiffness_n_per_m2,
                                   " must be > 0"));
    if (!(std::isfinite(seam_closing_speed_m_per_s) && seam_closing_speed_m_per_s > 0))
        return fail(detail::concat("seam_closing_speed_m_per_s = ", seam_closing_speed_m_per_s,
                                   " must be > 0"));
    if (!nonneg(air_drag_n_s_per_m3))
        return fail(detail::concat("air_drag_n_s_per_m3 = ", air_drag_n_s_per_m3, " must be >= 0"));
    if (!wind_m_per_s.allFinite()) return fail("wind_m_per_s is not finite");
    return true;
}

std::string StepSummary::brief_report() const {
    std::ostringstream os;
    os << to_string(termination) << ": " << newton_iterations << " Newton iterations, |g|inf "
       << gradient_inf_norm_n << " N (tol " << tolerance_n << "), E " << energy_j << " J, "
       << contacts << " contacts, " << self_contact_pairs << " self-contact pairs, stitch gap "
       << max_stitch_gap_m * 1e3 << " mm, " << seconds_total * 1e3 << " ms (assembly "
       << seconds_assembly * 1e3 << ", solve " << seconds_solve * 1e3 << ", contact "
       << seconds_contact * 1e3 << ")";
    os << ", " << factorisations << " factorisations (" << regularised_factorisations << " regularised)";
    if (substeps > 1) os << ", " << substeps << " substeps";
    if (released_steps > 0) os << ", " << released_steps << " released pressed-layer steps";
    if (!message.empty()) os << "; " << message;
    return os.str();
}

void Simulator::Impl::renumber() {
    solver.reset();
    pattern_ready = false;
    analysed_with_contacts = false;
    contact_blocks.clear();
    dof_index.assign(static_cast<std::size_t>(3 * x.rows()), -1);
    free_dofs = 0;
    for (Eigen::Index i = 0; i < x.rows(); ++i)
        if (!pinned[static_cast<std::size_t>(i)])
            for (int c = 0; c < 3; ++c) dof_index[static_cast<std::size_t>(3 * i + c)] = free_dofs++;
}

void Simulator::Impl::compute_rest_state() {
    // Lumped masses and rest areas: each face gives ρ_f A_f / 3 and A_f / 3 to its corners.
    mass = Eigen::VectorXd::Zero(x.rows());
    area = Eigen::VectorXd::Zero(x.rows());
    triangles.clear();
    triangles.reserve(static_cast<std::size_t>(mesh.face_count()));
    for (int f = 0; f < mesh.face_count(); ++f) {
        Eigen::Vector2d u[3];
        for (int c = 0; c < 3; ++c) u[c] = mesh.pattern.row(mesh.pattern_faces(f, c)).transpose();
        triangles.push_back(triangle_rest(u[0], u[1], u[2]));
        const double third = triangles.back().area_m2 / 3;
        for (int c = 0; c < 3; ++c) {
            area(mesh.faces(f, c)) += third;
            mass(mesh.faces(f, c)) += material_of(f).density_kg_per_m2 * third;
        }
    }
    hinge_rests.clear();
    bend_curves.clear();
    hinge_rests.reserve(hinges.size());
    bend_curves.reserve(hinges.size());
    for (const Hinge& h : hinges) {
        hinge_rests.push_back(hinge_rest(mesh, h));
        // A hinge between two materials bends with its first face's (documented in the header).
        bend_curves.push_back(bending_curve(material_of(h.faces[0]), hinge_rests.back()));
    }
    // The stiffness of the last step belongs to the old rest shape or material.
    k_stretch.clear();
    k_lagged.clear();
}

Simulator::Simulator(ClothMesh mesh, Material material, SimulatorOptions options)
    // `mesh` is copied, not moved: the face count is read in the same argument list, whose
    // evaluation order is unspecified (the copy is negligible next to any simulation).
    : Simulator(mesh, std::vector<Material>{std::move(material)},
                std::vector<int>(static_cast<std::size_t>(mesh.faces.rows()), 0), std::move(options)) {}

Simulator::Simulator(ClothMesh mesh, std::vector<Material> materials, std::vector<int> face_material,
                     SimulatorOptions options)
    : impl_(std::make_unique<Impl>()) {
    std::string why;
    require(options.is_valid(&why), "Simulator: options are invalid: ", why);
    require(!materials.empty(), "Simulator: materials is empty (need at least one)");
    for (std::size_t k = 0; k < materials.size(); ++k)
        require(materials[k].is_valid(&why), "Simulator: material ", k, " is invalid: ", why);
    mesh.validate();
    require(face_material.size() == static_cast<std::size_t>(mesh.face_count()),
            "Simulator: face_material has ", face_material.size(), " entries, the mesh has ",
            mesh.face_count(), " faces");
    for (std::size_t f = 0; f < face_material.size(); ++f)
        require(face_material[f] >= 0 && static_cast<std::size_t>(face_material[f]) < materials.size(),
                "Simulator: face_material[", f, "] = ", face_material[f], " is out of range [0, ",
                materials.size(), ")");
    Impl& m = *impl_;
    m.mesh = std::move(mesh);
    m.materials = std::move(materials);
    m.face_material = std::move(face_material);
    m.options = std::move(options);
    m.x = m.mesh.positions;
    m.v = Eigen::MatrixX3d::Zero(m.x.rows(), 3);
    m.pinned.assign(static_cast<std::size_t>(m.x.rows()), false);
    m.hinges = build_hinges(m.mesh);
    m.compute_rest_state();
    m.self_contact = internal::SelfContact(m.mesh.faces, m.mesh.vertex_count());
    m.set_rest_filter();
    m.renumber();
}

Simulator::~Simulator() = default;
Simulator::Simulator(Simulator&&) noexcept = default;
Simulator& Simulator::operator=(Simulator&&) noexcept = default;

void Simulator::pin(int vertex) {
    require(vertex >= 0 && vertex < impl_->x.rows(), "Simulator::pin: vertex ", vertex,
            " is out of range [0, ", impl_->x.rows(), ")");
    impl_->pinned[static_cast<std::size_t>(vertex)] = true;
    impl_->v.row(vertex).setZero();
    impl_->renumber();
}

void Simulator::set_pinned_position(int vertex, const Eigen::Vector3d& position_m) {
    require(vertex >= 0 && vertex < impl_->x.rows() && impl_->pinned[static_cast<std::size_t>(vertex)],
            "Simulator::set_pinned_position: vertex ", vertex, " is not a pinned vertex");
    require(position_m.allFinite(), "Simulator::set_pinned_position: position is not finite");
    impl_->x.row(vertex) = position_m.transpose();
}

const std::vector<bool>& Simulator::pinned() const { return impl_->pinned; }

void Simulator::set_obstacle(Obstacle obstacle) {
    impl_->obstacle = std::move(obstacle);
    impl_->obstacle_start = impl_->obstacle->positions();
}

void Simulator::move_obstacle(const Eigen::MatrixX3d& positions_m) {
    require(impl_->obstacle.has_value(), "Simulator::move_obstacle: there is no obstacle");
    impl_->obstacle->set_positions(positions_m);
}

void Simulator::clear_obstacle() {
    impl_->obstacle.reset();
    impl_->obstacle_start.resize(0, 3);
}

const Obstacle* Simulator::obstacle() const {
    return impl_->obstacle ? &*impl_->obstacle : nullptr;
}

void Simulator::set_stitches(const std::vector<Stitch>& stitches) {
    Impl& m = *impl_;
    const int n = m.mesh.vertex_count();
    for (std::size_t k = 0; k < stitches.size(); ++k) {
        const Stitch& s = stitches[k];
        require(s.a >= 0 && s.a < n && s.b >= 0 && s.b < n, "Simulator::set_stitches: stitch ", k,
                " joins vertices (", s.a, ", ", s.b, "), out of range [0, ", n, ")");
        require(s.a != s.b, "Simulator::set_stitches: stitch ", k, " joins vertex ", s.a, " to itself");
        require(std::isfinite(s.length_m) && s.length_m > 0, "Simulator::set_stitches: stitch ", k,
                " has length_m = ", s.length_m, ", must be > 0");
    }
    m.stitches = stitches;
    m.stitch_rest.resize(stitches.size());
    // Contact is ignored between any two vertices of a stitched group (transitively: where
    // three or four panels meet, as at an underarm, the corners not stitched directly to
    // each other would otherwise hold the seam open by the contact thickness).
    DisjointSets groups(n);
    for (std::size_t k = 0; k < stitches.size(); ++k) {
        m.stitch_rest[k] = (m.x.row(stitches[k].a) - m.x.row(stitches[k].b)).norm();
        groups.join(stitches[k].a, stitches[k].b);
    }
    std::map<int, std::vector<int>> members;
    for (const Stitch& st : stitches)
        for (int v : {st.a, st.b}) members[groups.find(v)].push_back(v);
    std::vector<std::pair<int, int>> excluded;
    for (auto& [root, list] : members) {
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
        for (std::size_t i = 0; i < list.size(); ++i)
            for (std::size_t j = i + 1; j < list.size(); ++j) excluded.emplace_back(list[i], list[j]);
    }
    m.self_contact = internal::SelfContact(m.mesh.faces, n, excluded);
    m.set_rest_filter();
    m.pattern_ready = false;
    m.solver.reset();
}

const std::vector<Stitch>& Simulator::stitches() const { return impl_->stitches; }

void Simulator::set_rest_positions(const Eigen::MatrixX2d& pattern_m) {
    Impl& m = *impl_;
    require(pattern_m.rows() == m.mesh.pattern.rows(), "Simulator::set_rest_positions: ", pattern_m.rows(),
            " pattern rows, the mesh has ", m.mesh.pattern.rows());
    // The same checks as construction (finite coordinates, every pattern triangle
    // counter-clockwise with area > 1e-12 m², naming the face), on the mesh as it would be.
    ClothMesh next = m.mesh;
    next.pattern = pattern_m;
    try {
        next.validate();
    } catch (const InvalidInput& e) {
        throw InvalidInput(std::string("Simulator::set_rest_positions: ") + e.what());
    }
    m.mesh.pattern = pattern_m;
    m.compute_rest_state();
    // Pattern neighbours within one layer (self-contact) are measured in the rest shape.
    m.set_rest_filter();
}

void Simulator::set_materials(std::vector<Material> materials) {
    Impl& m = *impl_;
    require(materials.size() == m.materials.size(), "Simulator::set_materials: ", materials.size(),
            " materials, the simulator was constructed with ", m.materials.size());
    std::string why;
    for (std::size_t k = 0; k < materials.size(); ++k)
        require(materials[k].is_valid(&why), "Simulator::set_materials: material ", k, " is invalid: ", why);
    m.materials = std::move(materials);
    m.compute_rest_state();
}


ContactReport Simulator::contact_report() const {
    const Impl& m = *impl_;
    ContactReport r;
    r.min_obstacle_distance_m = std::numeric_limits<double>::infinity();
    if (m.obstacle) {
        for (Eigen::Index i = 0; i < m.x.rows(); ++i) {
            const ObstacleQuery q = m.obstacle->closest(m.x.row(i).transpose(),
                                                        std::numeric_limits<double>::infinity());
            if (!q.found) continue;
            r.min_obstacle_distance_m = std::min(r.min_obstacle_distance_m, q.signed_distance_m);
            if (q.signed_distance_m < 0) {
                ++r.vertices_inside;
                if (-q.signed_distance_m > r.max_penetration_m) {
                    r.max_penetration_m = -q.signed_distance_m;
                    r.deepest_vertex = static_cast<int>(i);
                    r.deepest_obstacle_face = q.face;
                }
            }
        }
    }
    r.max_stitch_gap_m = m.max_stitch_gap(m.x);
    // A sewn garment is one surface: stitched vertices count as one (else the triangles on
    // the two sides of a closed seam, which touch along it, would count as intersecting).
    DisjointSets sewn(static_cast<int>(m.x.rows()));
    for (const Stitch& st : m.stitches) sewn.join(st.a, st.b);
    Eigen::MatrixX3i merged = m.mesh.faces;
    for (Eigen::Index f = 0; f < merged.rows(); ++f)
        for (int c = 0; c < 3; ++c) merged(f, c) = sewn.find(merged(f, c));
    r.self_intersections = count_self_intersections(m.x, merged);
    return r;
}

namespace {

// Sums the counters of `part` into `total` (termination/energy/norms come from the last part).
void accumulate(StepSummary& total, const StepSummary& part) {
    total.newton_iterations += part.newton_iterations;
    total.regularised_factorisations += part.regularised_factorisations;
    total.factorisations += part.factorisations;
    total.released_steps += part.released_steps;
    total.seconds_assembly += part.seconds_assembly;
    total.seconds_solve += part.seconds_solve;
    total.seconds_contact += part.seconds_contact;
    total.termination = part.termination;
    total.message = part.message;
    total.gradient_inf_norm_n = part.gradient_inf_norm_n;
    total.tolerance_n = part.tolerance_n;
    total.energy_j = part.energy_j;
    total.contacts = part.contacts;
    total.self_contact_pairs = part.self_contact_pairs;
    total.max_stitch_gap_m = part.max_stitch_gap_m;
}

}  // namespace

StepSummary Simulator::step() {
    const auto t0 = Clock::now();
    StepSummary s = impl_->backward_euler(impl_->options.time_step_s,
                                          impl_->options.max_step_halvings);
    s.seconds_total = seconds_since(t0);
    return s;
}

StepSummary Simulator::Impl::backward_euler(double h, int halvings_left) {
    Impl& m = *this;
    Eigen::MatrixX3d target = m.x + h * m.v;
    for (std::size_t i = 0; i < m.pinned.size(); ++i)
        if (m.pinned[i]) target.row(static_cast<Eigen::Index>(i)) = m.x.row(static_cast<Eigen::Index>(i));
    // Open seams close at the closing speed; the rest lengths only shrink.
    const std::vector<double> rest_before = m.stitch_rest;
    for (double& r : m.stitch_rest) r = std::max(0.0, r - m.options.seam_closing_speed_m_per_s * h);
    m.step_start = m.x;
    m.step_dt = h;
    // Start from the current positions: the inertial prediction could jump through the
    // obstacle or another layer, while every Newton step from here is kept collision-safe.
    Eigen::MatrixX3d p = m.x;
    StepSummary s = m.minimise(p, target, 1 / (h * h), m.options.step_relative_tolerance);
    m.step_dt = 0;
    if (s.usable()) {
        m.v = (p - m.x) / h;
        m.x = p;
        if (m.obstacle) m.obstacle_start = m.obstacle->positions();
        return s;
    }
    m.stitch_rest = rest_before;
    if (halvings_left == 0 || s.termination == StepTermination::cancelled) return s;
    // Retry as two half steps from the unchanged state.
    const Eigen::MatrixX3d x0 = m.x, v0 = m.v;
    StepSummary total = s;
    total.substeps = 0;
    for (int half = 0; half < 2; ++half) {
        const StepSummary part = backward_euler(h / 2, halvings_left - 1);
        accumulate(total, part);
        total.substeps += part.substeps;
        if (!part.usable()) {
            m.x = x0;
            m.v = v0;
            m.stitch_rest = rest_before;
            total.message = "failed even after halving the step: " + part.message;
            return total;
        }
    }
    total.message = detail::concat("step split into ", total.substeps, " substeps after: ", s.message);
    return total;
}

StepSummary Simulator::solve_static() {
    Impl& m = *impl_;
    Eigen::MatrixX3d p = m.x;
    std::fill(m.stitch_rest.begin(), m.stitch_rest.end(), 0.0);
    m.step_dt = 0;
    m.step_start = m.x;
    m.static_friction = m.options.static_friction;
    StepSummary s = m.minimise(p, m.x, 0, m.options.relative_tolerance);
    m.static_friction = false;
    if (s.termination != StepTermination::non_finite) {
        m.x = p;
        m.v.setZero();
        if (m.obstacle) m.obstacle_start = m.obstacle->positions();  // its motion so far is settled
    }
    return s;
}

const Eigen::MatrixX3d& Simulator::positions() const { return impl_->x; }
const Eigen::MatrixX3d& Simulator::velocities() const { return impl_->v; }

void Simulator::set_positions(const Eigen::MatrixX3d& positions_m) {
    require(positions_m.rows() == impl_->x.rows(), "Simulator::set_positions: ", positions_m.rows(),
            " rows, expected ", impl_->x.rows());
    require(positions_m.allFinite(), "Simulator::set_positions: positions are not finite");
    impl_->x = positions_m;
    impl_->k_lagged.clear();
    // The vertices may have jumped anywhere: their previous obstacle distances are unknown,
    // so the next contact update searches every vertex beyond the query radius too.
    impl_->contacts.clear();
}

void Simulator::set_velocities(const Eigen::MatrixX3d& velocities_m_per_s) {
    require(velocities_m_per_s.rows() == impl_->v.rows(), "Simulator::set_velocities: ",
            velocities_m_per_s.rows(), " rows, expected ", impl_->v.rows());
    require(velocities_m_per_s.allFinite(), "Simulator::set_velocities: velocities are not finite");
    impl_->v = velocities_m_per_s;
    for (std::size_t i = 0; i < impl_->pinned.size(); ++i)
        if (impl_->pinned[i]) impl_->v.row(static_cast<Eigen::Index>(i)).setZero();
}

const Eigen::VectorXd& Simulator::masses() const { return impl_->mass; }
const ClothMesh& Simulator::mesh() const { return impl_->mesh; }
const Material& Simulator::material() const { return impl_->materials.front(); }
const std::vector<Material>& Simulator::materials() const { return impl_->materials; }
const std::vector<int>& Simulator::face_material() const { return impl_->face_material; }
const SimulatorOptions& Simulator::options() const { return impl_->options; }

Eigen::MatrixX3d Simulator::forces() const {
    Impl copy = Impl(*impl_);  // refresh_stiffness mutates the frozen stiffness cache
    copy.refresh_stiffness(copy.x);
    copy.contacts.clear();
    Eigen::VectorXd g;
    const bool self = copy.options.self_contact;
    copy.options.self_contact = false;
    copy.potential(copy.x, &g, nullptr);
    copy.options.self_contact = self;
    Eigen::MatrixX3d f(copy.x.rows(), 3);
    for (Eigen::Index i = 0; i < f.rows(); ++i) f.row(i) = -g.segment<3>(3 * i).transpose();
    return f;
}

}  // namespace drape::cloth
