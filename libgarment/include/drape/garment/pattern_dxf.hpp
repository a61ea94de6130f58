// DXF export in the AAMA/ASTM D6673 style (R12 ASCII) for pattern CAD systems.
#pragma once

#include <drape/garment/pattern.hpp>

#include <filesystem>
#include <string>

namespace drape::garment {

/// AAMA layer numbers used by the export.
inline constexpr int kDxfLayerBoundary = 1;
inline constexpr int kDxfLayerNotches = 4;
inline constexpr int kDxfLayerGrain = 7;
inline constexpr int kDxfLayerInternal = 8;

/// The DXF text (units: cm, $MEASUREMENT = 1 metric): HEADER, TABLES (layers), BLOCKS with one
/// BLOCK per piece (closed boundary POLYLINE on layer 1 with chords <= max_chord_cm,
/// internal lines on 8, grain line on 7, notches on 4, piece name TEXT on 1), and
/// ENTITIES inserting each block at its layout position.
/// \throw drape::InvalidInput if the pattern is invalid or max_chord_cm <= 0.
std::string pattern_to_dxf(const Pattern& pattern, double max_chord_cm = 0.5);

/// Writes pattern_to_dxf() atomically. \throw drape::IoError on write failure.
void write_pattern_dxf(const std::filesystem::path& path, const Pattern& pattern,
                       double max_chord_cm = 0.5);

}  // namespace drape::garment
