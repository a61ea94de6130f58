// The fast re-drape of one garment on a fixed posed body for garment recovery (issue 21,
// "Speed is a design constraint"): the sizing G and the material C change, the mesh does
// not. Built once from a finished drape; every evaluation morphs the rest shape
// (PatternMorph, cloth::Simulator::set_rest_positions), warm-starts from the drape and
// settles with a few dynamic steps. See docs/dressing.md, "Fast re-drape for recovery".
#pragma once

#include <drape/cloth/material.hpp>
#include <drape/garment/drape_garment.hpp>
#include <drape/garment/dress_outfit.hpp>
#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/garment_sizing.hpp>
#include <drape/garment/morph_mesh.hpp>
#include <drape/garment/pattern.hpp>

#include <Eigen/Core>

#include <memory>
#include <string>

namespace drape::garment {

struct SizingDrapeOptions {
    /// Simulator settings, waistband and tolerances as the drape used (keep them equal to
    /// the DressOutfitOptions::drape the base drape was made with). Its step budget fields
    /// (min_steps, max_steps, ...) are not used: see below.
    DrapeOptions drape;
    /// Time step of the re-drape (s), replacing drape.simulator.time_step_s; 0: the drape's.
    /// Twice the drape's 10 ms by default: about half the steps to settle, the same result
    /// (docs/benchmarks.md, bench-sizing-drape).
    double time_step_s = 0.02;
    /// Dynamic steps at most per evaluation, >= 1.
    int max_steps = 60;
    /// Dynamic steps always taken, >= 0 and <= max_steps.
    int min_steps = 3;
    /// The evaluation has settled (converged) when the kinetic energy per unit mass is below
    /// this (J/kg; 1e-4 ≈ 1.4 cm/s RMS), as DrapeOptions::settled_kinetic_energy_j_per_kg.
    double settled_kinetic_energy_j_per_kg = 1e-4;
    /// Each evaluation starts from the base drape (the drape the object was built from) or
    /// from the last evaluation that settled. The base is the default: a bad candidate (a
    /// sizing that slides off) cannot poison the next, and results do not depend on the
    /// order of evaluation (a swarm's particles give the same objective in any order).
    enum class WarmStart { base, last_settled } warm_start = WarmStart::base;
    /// With a body set by set_body: the steps over which the body moves from the base pose
    /// to it at the start of each evaluation (the cloth follows by contact), before the
    /// settling steps; >= 1.
    int body_blend_steps = 8;
    bool is_valid(std::string* why = nullptr) const;
};

/// What one evaluation gives.
struct SizingDrapeResult {
    /// #V x 3, world, metres: the garment's vertices (GarmentMesh numbering: stitched
    /// vertices at their welded position).
    Eigen::MatrixX3d positions;
    bool converged = false;          ///< settled within max_steps, every step usable
    double penetration_max_m = 0;    ///< deepest vertex inside the body
    double seam_gap_max_m = 0;       ///< 0 when the seams are welded
    int self_intersections = 0;      ///< intersecting non-adjacent triangle pairs
    int steps = 0;                   ///< dynamic steps taken
    int newton_iterations = 0;       ///< over all steps
    double kinetic_energy_j_per_kg = 0;  ///< at the end
    double seconds = 0;              ///< wall time of evaluate()
    std::string message;             ///< why not converged, if not
    /// Converged, seams closed and penetration within the drape's tolerances, no
    /// self-intersection.
    bool usable(const DrapeOptions& tolerances) const;
};

/// One garment re-draped for many sizings and materials on a fixed posed body.
///
/// Thread safety: no shared mutable state. Use one object per thread: copies are cheap
/// (the morph coordinates and base drape are shared read-only; the copy builds its own
/// simulator, ~ms at coarse edges). const member functions may run concurrently.
///
/// Outfits: each garment gets its own SizingDrape on the body alone; the other garments
/// are not part of it (no layering: a top over a skirt's waistband is evaluated as if the
/// skirt were not there). The final full drape of the outfit is the caller's dress_outfit.
class SizingDrape {
public:
    /// \param pattern the pattern of `sizing`, which `mesh` meshes.
    /// \param draped the finished drape of `mesh` (#V x 3, world, metres), e.g.
    ///        DressedOutfit::positions[g].
    /// \param body_vertices the posed body (#B x 3), \param body_faces its faces.
    /// \param material the garment's fabric (the waistband is made of it, stiffened, as in
    ///        dress_and_drape; its faces are chosen once, on the base mesh, and kept for
    ///        every sizing).
    /// \throw drape::InvalidInput if the options, pattern, mesh, positions, body or material
    ///        are invalid or do not fit together.
    SizingDrape(const Pattern& pattern, const GarmentSizing& sizing, const GarmentMesh& mesh,
                const Eigen::MatrixX3d& draped, const Eigen::MatrixX3d& body_vertices,
                const Eigen::MatrixX3i& body_faces, const cloth::Material& material,
                const SizingDrapeOptions& options = {});
    /// Garment `garment` of a dress_outfit result, on its posed body (body_faces: the body
    /// model's faces), in `material` (the GarmentRequest's).
    /// \throw drape::InvalidInput if `garment` is out of range, or as above.
    SizingDrape(const DressedOutfit& outfit, int garment, const Eigen::MatrixX3i& body_faces,
                const cloth::Material& material, const SizingDrapeOptions& options = {});
    ~SizingDrape();
    SizingDrape(const SizingDrape& other);
    SizingDrape& operator=(const SizingDrape& other);
    SizingDrape(SizingDrape&&) noexcept;
    SizingDrape& operator=(SizingDrape&&) noexcept;

    /// Re-drapes at sizing `g` (the template's type) with the current material: the pattern
    /// of g, the mesh morphed onto it, the simulator's rest shape set, the state reset to the
    /// warm start, then dynamic steps until settled (see the options). `g` becomes the
    /// current sizing, also when the result did not converge.
    /// \throw drape::InvalidInput if g is of another type, out of its ranges (make_pattern),
    ///        or too far from the base sizing for the mesh (PatternMorph::morph: a triangle
    ///        inverts); the object is then unchanged.
    SizingDrapeResult evaluate(const GarmentSizing& g);
    /// Re-drapes at the current sizing and material (after set_material).
    SizingDrapeResult evaluate();
    /// The fabric of the next evaluations (the waistband follows it). \throw drape::InvalidInput
    /// if invalid.
    void set_material(const cloth::Material& material);
    /// The body of the next evaluations: the base body's vertices moved (#B x 3, same faces,
    /// world metres), e.g. posed slightly differently (the joint material-pose search, paper
    /// Algorithm 2). Each evaluation then starts from the base drape on the base body and
    /// moves the body to these vertices over options().body_blend_steps steps before
    /// settling. An empty matrix returns to the base body.
    /// \throw drape::InvalidInput on a shape mismatch or a non-finite value.
    void set_body(const Eigen::MatrixX3d& body_vertices);

    const GarmentSizing& sizing() const;        ///< the current sizing
    const cloth::Material& material() const;    ///< the current fabric
    const GarmentSizing& base_sizing() const;   ///< the sizing of the base drape
    const Eigen::MatrixX3d& base_positions() const;  ///< the base drape, #V x 3
    /// The garment mesh at the current sizing (morphed; for export with the positions).
    GarmentMesh mesh() const;
    const SizingDrapeOptions& options() const;

private:
    struct Shared;
    struct State;
    std::shared_ptr<const Shared> shared_;
    std::unique_ptr<State> state_;
};

}  // namespace drape::garment
