// Assembly of the incremental potential: the elements (stretching, bending), gravity,
// stitches, body contact planes, friction, self-contact, air drag and inertia, with the
// gradient and the Hessian scattered into a fixed sparsity pattern.
#include "simulator_impl.hpp"

#include <drape/core/parallel_for.hpp>

#include <algorithm>

namespace drape::cloth {

void Simulator::Impl::refresh_stiffness(const Eigen::MatrixX3d& p, bool relax) {
    k_stretch.resize(triangles.size());
    core::parallel_for(mesh.face_count(), [&](int f) {
        k_stretch[static_cast<std::size_t>(f)] = stretching_stiffness(
            material_of(f), green_strain(face_positions(p, f), triangles[static_cast<std::size_t>(f)]));
    });
    if (!relax) return;
    if (k_lagged.size() == k_stretch.size())
        for (std::size_t f = 0; f < k_stretch.size(); ++f) {
            StretchingStiffness& k = k_stretch[f];
            const StretchingStiffness& o = k_lagged[f];
            k.k_uu = 0.5 * (k.k_uu + o.k_uu);
            k.k_uv = 0.5 * (k.k_uv + o.k_uv);
            k.k_vv = 0.5 * (k.k_vv + o.k_vv);
            k.k_shear = 0.5 * (k.k_shear + o.k_shear);
        }
    k_lagged = k_stretch;
}

int Simulator::Impl::slot_in(const Eigen::SparseMatrix<double>& m, int r, int c) {
    const int* inner = m.innerIndexPtr();
    const int* begin = inner + m.outerIndexPtr()[c];
    const int* end = inner + m.outerIndexPtr()[c + 1];
    const int* it = std::lower_bound(begin, end, r);
    return (it != end && *it == r) ? static_cast<int>(it - inner) : -1;
}

void Simulator::Impl::add_block_entries(std::vector<Eigen::Triplet<double>>& entries, const int* verts, int n) const {
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b)
            for (int ca = 0; ca < 3; ++ca)
                for (int cb = 0; cb < 3; ++cb) {
                    const int r = dof(verts[a], ca), c = dof(verts[b], cb);
                    if (r >= 0 && c >= 0) entries.emplace_back(r, c, 0.0);
                }
}

void Simulator::Impl::fill_slots(const int* verts, int n, int* out) const {
    for (int b = 0; b < n; ++b)
        for (int cb = 0; cb < 3; ++cb)
            for (int a = 0; a < n; ++a)
                for (int ca = 0; ca < 3; ++ca) {
                    const int r = dof(verts[a], ca), c = dof(verts[b], cb);
                    out[(3 * b + cb) * 3 * n + 3 * a + ca] = (r >= 0 && c >= 0) ? slot_in(pattern, r, c) : -1;
                }
}

void Simulator::Impl::build_pattern() {
    std::vector<Eigen::Triplet<double>> entries;
    for (int f = 0; f < mesh.face_count(); ++f) {
        const int verts[3] = {mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2)};
        add_block_entries(entries, verts, 3);
    }
    for (const Hinge& h : hinges) add_block_entries(entries, h.v.data(), 4);
    for (const Stitch& st : stitches) {
        const int verts[2] = {st.a, st.b};
        add_block_entries(entries, verts, 2);
    }
    for (int i = 0; i < mesh.vertex_count(); ++i) add_block_entries(entries, &i, 1);
    pattern.resize(free_dofs, free_dofs);
    pattern.setFromTriplets(entries.begin(), entries.end());
    pattern.makeCompressed();
    face_slots.assign(static_cast<std::size_t>(81 * mesh.face_count()), -1);
    core::parallel_for(mesh.face_count(), [&](int f) {
        const int verts[3] = {mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2)};
        fill_slots(verts, 3, face_slots.data() + 81 * f);
    });
    hinge_slots.assign(144 * hinges.size(), -1);
    core::parallel_for(static_cast<int>(hinges.size()), [&](int h) {
        fill_slots(hinges[static_cast<std::size_t>(h)].v.data(), 4,
                   hinge_slots.data() + 144 * h);
    });
    stitch_slots.assign(36 * stitches.size(), -1);
    for (std::size_t k = 0; k < stitches.size(); ++k) {
        const int verts[2] = {stitches[k].a, stitches[k].b};
        fill_slots(verts, 2, stitch_slots.data() + 36 * k);
    }
    vertex_slots.assign(static_cast<std::size_t>(9 * mesh.vertex_count()), -1);
    for (int i = 0; i < mesh.vertex_count(); ++i) fill_slots(&i, 1, vertex_slots.data() + 9 * i);
    diagonal_slots.resize(static_cast<std::size_t>(free_dofs));
    for (int d = 0; d < free_dofs; ++d) diagonal_slots[static_cast<std::size_t>(d)] = slot_in(pattern, d, d);
    contact_pattern.resize(free_dofs, free_dofs);
    contact_pattern.setZero();
    contact_blocks.clear();
    analysed_with_contacts = false;
    solver.reset();
    pattern_ready = true;
}

bool Simulator::Impl::update_contact_blocks(const std::vector<internal::PairHessian>& pairs) {
    bool grew = false;
    for (const internal::PairHessian& ph : pairs)
        for (int a = 0; a < 4; ++a)
            for (int b = a + 1; b < 4; ++b) {
                int va = ph.pair.v[static_cast<std::size_t>(a)], vb = ph.pair.v[static_cast<std::size_t>(b)];
                if (va == vb || pinned[static_cast<std::size_t>(va)] || pinned[static_cast<std::size_t>(vb)]) continue;
                if (va > vb) std::swap(va, vb);
                grew |= contact_blocks.emplace(va, vb).second;
            }
    if (grew) {
        std::vector<Eigen::Triplet<double>> entries;
        for (const auto& [a, b] : contact_blocks) {
            const int verts[2] = {a, b};
            add_block_entries(entries, verts, 2);
        }
        contact_pattern.resize(free_dofs, free_dofs);
        contact_pattern.setFromTriplets(entries.begin(), entries.end());
        contact_pattern.makeCompressed();
    }
    return grew;
}

double Simulator::Impl::potential(const Eigen::MatrixX3d& p, Eigen::VectorXd* gradient, double* values,
                 std::vector<internal::PairHessian>* pair_hessians) {
    const bool want_g = gradient != nullptr, want_h = values != nullptr;
    const int nf = mesh.face_count();
    const int nh = static_cast<int>(hinges.size());
    face_energy.resize(static_cast<std::size_t>(nf));
    hinge_energy.resize(static_cast<std::size_t>(nh));
    if (want_g) {
        face_grad.resize(static_cast<std::size_t>(nf));
        hinge_grad.resize(static_cast<std::size_t>(nh));
    }
    if (want_h) {
        face_hess.resize(static_cast<std::size_t>(nf));
        hinge_hess.resize(static_cast<std::size_t>(nh));
    }
    core::parallel_for(nf, [&](int f) {
        const auto fs = static_cast<std::size_t>(f);
        face_energy[fs] = stretching_energy(face_positions(p, f), triangles[fs], k_stretch[fs],
                                            want_g ? &face_grad[fs] : nullptr,
                                            want_h ? &face_hess[fs] : nullptr,
                                            hessian_mode);
    }, 128);
    // Bending's exact Hessian needs the dihedral angle's second derivatives (forward-mode
    // numbers, ~4x the cost); its Gauss-Newton matrix is exact up to (θ−θ̄)∇²θ, small for
    // cloth, so time steps use it while stretching (whose compressed elements are what
    // make the projected Newton converge only linearly) stays exact.
    const HessianMode bending_mode =
        hessian_mode == HessianMode::exact && !exact_hessians ? HessianMode::gauss_newton : hessian_mode;
    core::parallel_for(nh, [&](int h) {
        const auto hs = static_cast<std::size_t>(h);
        hinge_energy[hs] = bending_energy(hinge_positions(p, hinges[hs]), hinge_rests[hs],
                                          bend_curves[hs], want_g ? &hinge_grad[hs] : nullptr,
                                          want_h ? &hinge_hess[hs] : nullptr, bending_mode);
    }, 128);

    double e = 0;
    if (gradient) gradient->setZero(3 * p.rows());
    auto scatter = [&](const int* verts, int n, const double* g, const double* hm, const int* slots) {
        if (want_g)
            for (int a = 0; a < n; ++a)
                for (int ca = 0; ca < 3; ++ca) (*gradient)(3 * verts[a] + ca) += g[3 * a + ca];
        if (want_h)
            for (int k = 0; k < 9 * n * n; ++k)
                if (slots[k] >= 0) values[slots[k]] += hm[k];
    };
    for (int f = 0; f < nf; ++f) {
        const auto fs = static_cast<std::size_t>(f);
        e += face_energy[fs];
        if (want_g || want_h) {
            const int verts[3] = {mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2)};
            scatter(verts, 3, want_g ? face_grad[fs].data() : nullptr,
                    want_h ? face_hess[fs].data() : nullptr,
                    want_h ? face_slots.data() + 81 * f : nullptr);
        }
    }
    for (int h = 0; h < nh; ++h) {
        const auto hs = static_cast<std::size_t>(h);
        e += hinge_energy[hs];
        if (want_g || want_h)
            scatter(hinges[hs].v.data(), 4, want_g ? hinge_grad[hs].data() : nullptr,
                    want_h ? hinge_hess[hs].data() : nullptr,
                    want_h ? hinge_slots.data() + 144 * h : nullptr);
    }
    // Gravity.
    for (Eigen::Index i = 0; i < p.rows(); ++i) {
        e -= mass(i) * options.gravity_m_per_s2.dot(p.row(i).transpose());
        if (want_g) gradient->segment<3>(3 * i) -= mass(i) * options.gravity_m_per_s2;
    }
    // Stitches.
    Vector6d g6;
    Matrix6d h6;
    for (std::size_t k = 0; k < stitches.size(); ++k) {
        const Stitch& st = stitches[k];
        const double ks = options.stitch_stiffness_n_per_m2 * st.length_m;
        e += stitch_energy(p.row(st.a).transpose(), p.row(st.b).transpose(), stitch_rest[k], ks,
                           want_g ? &g6 : nullptr, want_h ? &h6 : nullptr,
                           exact_hessians ? hessian_mode : HessianMode::projected_psd);
        const int verts[2] = {st.a, st.b};
        if (want_g || want_h)
            scatter(verts, 2, want_g ? g6.data() : nullptr, want_h ? h6.data() : nullptr,
                    want_h ? stitch_slots.data() + 36 * k : nullptr);
    }
    // Obstacle contact: ½ k (h − n·(x − c))² against each contact plane (see planes).
    Eigen::Vector3d g3, gf;
    Eigen::Matrix3d h3, hf;
    const double eps = friction_epsilon();
    if (obstacle) {
        // The contact planes of this step or static solve (exact quadratic energies).
        for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(plane_of_vertex.size()); ++i) {
            for (const int plane : plane_of_vertex[static_cast<std::size_t>(i)]) {
                if (plane < 0) continue;
                const int vi = static_cast<int>(i);
                const auto& [point, normal] = planes[static_cast<std::size_t>(plane)];
                const double ei = plane_contact_energy(p.row(i).transpose(), point, normal,
                                                       options.contact_thickness_m,
                                                       options.contact_stiffness_n_per_m3 * area(i),
                                                       want_g ? &g3 : nullptr, want_h ? &h3 : nullptr,
                                                       options.contact_inside_stiffness_factor);
                if (ei <= 0) continue;
                e += ei;
                scatter(&vi, 1, want_g ? g3.data() : nullptr, want_h ? h3.data() : nullptr,
                        want_h ? vertex_slots.data() + 9 * i : nullptr);
            }
        }
    }
    if (friction_active())
        for (const FrictionContact& c : friction) {
            const int i = c.vertex;
            e += friction_energy((p.row(i) - step_start.row(i)).transpose() - c.surface_motion, c.normal, c.normal_force,
                                 options.obstacle_friction, eps, want_g ? &gf : nullptr,
                                 want_h ? &hf : nullptr, options.friction_majorize_slip_m);
            if (want_g || want_h)
                scatter(&i, 1, want_g ? gf.data() : nullptr, want_h ? hf.data() : nullptr,
                        want_h ? vertex_slots.data() + 9 * i : nullptr);
        }
    // Self-contact.
    if (options.self_contact && !self_contact.candidates().empty()) {
        internal::SelfContactParams params{options.contact_thickness_m, self_contact_stiffness()};
        e += self_contact.energy(p, params, gradient, want_h ? pair_hessians : nullptr,
                                 exact_hessians ? hessian_mode : HessianMode::gauss_newton);
    }
    // Cloth–cloth friction: μ λ f₀ of the closest points' relative slip u = Σ w_c Δx_c
    // (frame lagged); gradient w_c ∇f₀, Hessian (w wᵀ) ⊗ ∇²f₀ (PSD).
    if (friction_active())
        for (const PairFriction& pf : pair_friction) {
            const auto& v = pf.frame.pair.v;
            const Eigen::Vector4d& w = pf.frame.weights;
            Eigen::Vector3d u = Eigen::Vector3d::Zero();
            for (int c = 0; c < 4; ++c) u += w(c) * (p.row(v[static_cast<std::size_t>(c)]) - step_start.row(v[static_cast<std::size_t>(c)])).transpose();
            e += friction_energy(u, pf.frame.normal, pf.normal_force, options.cloth_friction, eps,
                                 want_g ? &gf : nullptr, want_h ? &hf : nullptr);
            if (want_g)
                for (int c = 0; c < 4; ++c) gradient->segment<3>(3 * v[static_cast<std::size_t>(c)]) += w(c) * gf;
            if (want_h && pair_hessians) {
                internal::PairHessian ph;
                ph.pair = pf.frame.pair;
                for (int a = 0; a < 4; ++a)
                    for (int b = 0; b < 4; ++b) ph.hessian.block<3, 3>(3 * a, 3 * b) = w(a) * w(b) * hf;
                pair_hessians->push_back(ph);
            }
        }
    // Air drag: c A/(2Δt) |x − x₀ − Δt w|², whose gradient is c A (v − w).
    if (step_dt > 0 && options.air_drag_n_s_per_m3 > 0) {
        for (Eigen::Index i = 0; i < p.rows(); ++i) {
            const double c = options.air_drag_n_s_per_m3 * area(i) / step_dt;
            const Eigen::Vector3d d = (p.row(i) - step_start.row(i)).transpose() - step_dt * options.wind_m_per_s;
            e += 0.5 * c * d.squaredNorm();
            if (want_g) gradient->segment<3>(3 * i) += c * d;
            if (want_h)
                for (int k = 0; k < 3; ++k) {
                    const int s = vertex_slots[static_cast<std::size_t>(9 * i + 4 * k)];
                    if (s >= 0) values[s] += c;
                }
        }
    }
    return e;
}

double Simulator::Impl::incremental_potential(const Eigen::MatrixX3d& q, const Eigen::MatrixX3d& target,
                                              double inertia_weight, Eigen::VectorXd* g, double* values,
                                              std::vector<internal::PairHessian>* ph) {
    double e = potential(q, g, values, ph);
    if (inertia_weight > 0) {
        const Eigen::MatrixX3d d = q - target;
        e += 0.5 * inertia_weight * (mass.transpose() * d.rowwise().squaredNorm()).value();
        if (g)
            for (Eigen::Index i = 0; i < q.rows(); ++i)
                g->segment<3>(3 * i) += inertia_weight * mass(i) * d.row(i).transpose();
    }
    return e;
}

}  // namespace drape::cloth
