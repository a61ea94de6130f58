// The phases of drape_garment (not installed): drape_garment.cpp calls them in order.
#pragma once

#include <drape/cloth/simulator.hpp>
#include <drape/garment/drape_garment.hpp>
#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/pattern.hpp>

#include <Eigen/Core>

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace drape::garment::detail {

/// ½ Σ m v² of the simulator's state (J).
double kinetic_energy(const cloth::Simulator& sim);

/// The welded simulation mesh of a garment: one vertex per stitched group (at the mean of
/// its members' positions and velocities), faces renumbered; pattern coordinates stay per
/// face corner (each panel keeps its own rest shape). Not validated.
struct Welded {
    cloth::ClothMesh mesh;
    std::vector<int> vertex_of;  ///< garment vertex -> welded vertex
};
Welded weld(const cloth::ClothMesh& source, const Eigen::MatrixX3d& positions, const Eigen::MatrixX3d& velocities,
            const std::vector<std::array<int, 2>>& stitches, Eigen::MatrixX3d* welded_velocities);

/// The garments of an outfit as one mesh: vertices, faces, stitches and boundary loops
/// renumbered one garment after the other (garment g's vertices start at first_vertex[g];
/// a last entry holds the total); each garment's flat layout is shifted 10 m along u so that
/// no two garments share pattern space.
GarmentMesh concatenate(const std::vector<GarmentMesh>& meshes, std::vector<int>* first_vertex);

/// The fabrics of an outfit concatenated in `meshes`' order: materials (one per garment)
/// followed by their waistband versions; face_material gives each face its garment's fabric,
/// or garment g's waistband fabric (index n + g) on its waistband faces (waistband_faces).
void outfit_fabrics(const std::vector<Pattern>& patterns, const std::vector<GarmentMesh>& meshes,
                    const std::vector<cloth::Material>& materials, double waistband_width_cm,
                    double waistband_stretching_factor, std::vector<cloth::Material>& fabrics,
                    std::vector<int>& face_material);

/// Throws drape::InvalidInput unless the options, materials, per-face materials, initial
/// positions (#V x 3) and body path (each #B x 3) fit the garment mesh.
void check_drape_inputs(const GarmentMesh& mesh, const Eigen::MatrixX3d& initial_positions,
                        const std::vector<Eigen::MatrixX3d>& body_path, const std::vector<cloth::Material>& materials,
                        const std::vector<int>& face_material, const DrapeOptions& options);

/// One drape of a garment: the simulator with the body as obstacle and the garment's
/// stitches, and the summary so far. The arguments must outlive it.
class DrapeRun {
public:
    /// Set-up: the simulator at the dressed state, its stitches, the dressed state's contact
    /// report and the schedule of the body's motion along its path.
    DrapeRun(const GarmentMesh& mesh, const Eigen::MatrixX3d& initial_positions,
             const std::vector<Eigen::MatrixX3d>& body_path, const Eigen::MatrixX3i& body_faces,
             const std::vector<cloth::Material>& materials, const std::vector<int>& face_material,
             const DrapeOptions& options);

    /// A dressed state that intersects itself is stepped without self-contact until it does
    /// not (at most DrapeOptions::max_untangle_steps). Returns false when the caller
    /// cancelled; out_positions (#V x 3) then holds the state reached.
    bool untangle(Eigen::MatrixX3d& out_positions);

    /// Steps while the seams close (welded once closed), the body moves along its path and
    /// the cloth settles; sets the termination. Returns false when a step failed or the
    /// caller cancelled.
    bool close_seams_and_settle();

    /// Whether the last stepping ended at rest.
    bool settled() const { return settled_; }

    /// The static solve from the settled state on a twin simulator, kept if it converged
    /// cleanly; else equilibrium by stepping (DrapeOptions::fallback_steps).
    void solve_static();

    /// At rest with crossing layers: untangled against the final body and stepped on to
    /// rest (DrapeOptions::repair_crossings), kept only if better; else the state and
    /// summary are as before.
    void repair_crossings();

    /// At rest but pressed deeper than the tolerance into the body: stepped on to rest with
    /// the penalty behind the body's surface stiffer (DrapeOptions::contact_stiffening),
    /// kept only if better; else the state and summary are as before.
    void stiffen_contact();

    /// The final measurements into the summary; out_positions (#V x 3) the garment's.
    void measure(Eigen::MatrixX3d& out_positions);

    const DrapeSummary& summary() const { return summary_; }

private:
    bool run_steps(int budget, int min_steps, DrapePhase phase);
    /// Appends to the remarks that end up in the summary's message.
    void note(const std::string& text);
    /// The contact report of the current state, computed once per state (it counts the
    /// cloth's crossings: the repairs at rest and measure() share it).
    const cloth::ContactReport& rest_report();
    /// One try at a better rest state: a fresh simulator with `options` from `positions`
    /// and `velocities` (simulation vertices) is stepped to rest (at most fallback_steps);
    /// kept if at rest with the seams closed and `better` says so. Else the simulator at
    /// rest and the summary (but its step count) come back, and `why` says what the try
    /// reached. false also when cancelled (the summary says so, the state reached is kept).
    bool retry_at_rest(const cloth::SimulatorOptions& options, const Eigen::MatrixX3d& positions,
                       const Eigen::MatrixX3d& velocities,
                       const std::function<bool(const cloth::ContactReport&)>& better, std::string* why);
    void weld_now();
    Eigen::MatrixX3d garment_positions(const Eigen::MatrixX3d& x) const;

    const GarmentMesh& mesh_;
    const Eigen::MatrixX3d& initial_positions_;
    const std::vector<Eigen::MatrixX3d>& body_path_;
    const std::vector<cloth::Material>& materials_;
    const std::vector<int>& face_material_;
    const DrapeOptions& options_;
    int nv_;
    cloth::Simulator sim_;
    std::vector<int> sim_vertex_;  // garment vertex -> simulation vertex (identity until welded)
    DrapeSummary summary_;
    double total_mass_ = 0;
    std::string notes_;
    bool moving_ = false;
    int motion_steps_ = 0;  // steps of the body motion taken
    int motion_total_ = 0;
    double motion_s_ = 0;
    bool weld_tried_ = false;
    bool settled_ = false;
    Eigen::MatrixX3d progress_positions_;
    std::optional<cloth::ContactReport> rest_report_;  // of the current state, once asked for
};

}  // namespace drape::garment::detail
