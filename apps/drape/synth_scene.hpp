// The files of a synthetic scene (docs/synthetic.md, "Files of a scene"): what
// drape::synth makes (libsynth), written as image_midday.png, image_sunset.png,
// labels.png, strokes.png, joints.json, truth.json and summary.json, and the choices of
// `drape synth` / a suite file read into synth::SynthOptions.
#pragma once

#include <drape/synth/synth_options.hpp>
#include <drape/synth/synth_scene.hpp>

#include <filesystem>
#include <string>

namespace drape::app {

/// The named choices of `drape synth` (flags or suite keys); "random" draws from the seed.
struct SynthChoices {
    /// "skirt", "pants", "tshirt", "dress", "tshirt+pants", "tshirt+skirt" or "random".
    std::string garment = "random";
    std::string pose = "random";      ///< "a" (A-pose), "b" (arms down), "c" (walking), "random"
    std::string material = "random";  ///< a built-in measured fabric name, or "random"
};

/// `base` with the garments, pose and fabric of `choices`.
/// \throw drape::InvalidInput naming the flag and value for an unknown garment or pose, or
///        an outfit that is not a t-shirt over pants or a skirt.
synth::SynthOptions with_choices(synth::SynthOptions base, const SynthChoices& choices);

/// Samples, makes and writes the scene of `options` into `dir` (created if needed).
/// Files hold no timings (they are in the returned summary only).
/// \throw drape::InvalidInput, drape::IoError; std::runtime_error if body shaping or
///        meshing fails.
synth::SynthSummary make_and_write_synth_scene(const synth::SynthOptions& options, const std::filesystem::path& dir);

}  // namespace drape::app
