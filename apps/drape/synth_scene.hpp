// The files of a synthetic scene (docs/synthetic.md, "Files of a scene"): what
// drape::synth makes (libsynth), written as image_midday.png, image_sunset.png,
// labels.png, strokes.png, joints.json, truth.json and summary.json, and the choices of
// `drape synth` / a suite file read into synth::SynthOptions.
#pragma once

#include <drape/synth/synth_options.hpp>
#include <drape/synth/synth_scene.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace drape::app {

/// The named choices of `drape synth` (flags or suite keys); "random" draws from the seed.
struct SynthChoices {
    /// "skirt", "pants", "tshirt", "dress", "tshirt+pants", "tshirt+skirt" or "random".
    std::string garment = "random";
    std::string pose = "random";      ///< "a" (A-pose), "b" (arms down), "c" (walking), "random"
    std::string material = "random";  ///< a built-in measured fabric name, or "random"
    /// "none" (plain), "stripes", "checks", "dots", or "sampled" (drawn with the look).
    std::string print = "sampled";
};

/// `base` with the garments, pose, fabric and print of `choices`.
/// \throw drape::InvalidInput naming the flag and value for an unknown garment, pose or print, or
///        an outfit that is not a t-shirt over pants or a skirt.
synth::SynthOptions with_choices(synth::SynthOptions base, const SynthChoices& choices);

/// Samples, makes and writes the scene of `options` into `dir` (created if needed).
/// Files hold no timings (they are in the returned summary only).
/// \throw drape::InvalidInput, drape::IoError; std::runtime_error if body shaping or
///        meshing fails.
synth::SynthSummary make_and_write_synth_scene(const synth::SynthOptions& options, const std::filesystem::path& dir);

/// The print check of a scene (docs/synthetic.md, "Plain and printed"): the scene's files
/// as make_and_write_synth_scene, plus print_none.png, print_stripes.png, print_checks.png
/// and print_dots.png (its drape rendered under mid-day light with each print) and
/// print_check.json (P per garment and print, the printed / plain ratios). With `reuse`
/// and those images and labels.png present, the scene is only sampled again (no drape, no
/// render) and P re-measured on them. Returns print_check.json's content; `summary`
/// receives the drape's summary when it was made. P is measured with `detector`.
/// \pre !options.print (the print check renders every kind itself)
/// \throw drape::InvalidInput, drape::IoError; std::runtime_error as make_and_write_synth_scene.
nlohmann::json make_and_write_print_check(const synth::SynthOptions& options, const std::filesystem::path& dir,
                                          bool reuse, synth::SynthSummary* summary,
                                          const vision::WrinkleOptions& detector = {});

}  // namespace drape::app
